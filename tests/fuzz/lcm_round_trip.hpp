#pragma once
// Encode . decode for the thx_msgs types, shared by the LCM message and log reader fuzz bodies:
// what try_decode accepts must re-encode to exactly the bytes it consumed, so no type loses or
// invents content (e.g. at an embedded NUL in a string).
#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <thx_msgs/protocol.hpp>
#include <type_traits>
#include <vector>

namespace thx::fuzz::lcm_round_trip {

using Failure = std::optional<std::string>;
using Bytes = std::vector<std::uint8_t>;

template <class T>
Bytes encoded(const T& m) {
  Bytes b(std::size_t(m.getEncodedSize()));
  m.encode(b.data(), 0, int(b.size()));
  return b;
}

template <class T>
Failure roundTrip(std::span<const std::uint8_t> data) {
  T m;
  const int n = thx_msgs::try_decode(data.data(), data.size(), m);
  if (n < 0) return std::nullopt;
  if constexpr (std::is_same_v<T, thx_msgs::contact_batch_t>) {
    if (!thx_msgs::batch_count_consistent(m)) return std::string("contact_batch_t: count differs from samples");
  }
  if constexpr (std::is_same_v<T, thx_msgs::physics_contacts_t>) {
    if (!thx_msgs::path_count_consistent(m)) return std::string("physics_contacts_t: count differs from path");
  }
  const Bytes again = encoded(m);
  if (again.size() != std::size_t(n) || !std::equal(again.begin(), again.end(), data.begin()))
    return std::string(T::getTypeName()) + ": try_decode accepted " + std::to_string(n) +
           " bytes that re-encode differently (" + std::to_string(again.size()) + " bytes)";
  return std::nullopt;
}

inline Failure everyType(std::span<const std::uint8_t> data) {
  using namespace thx_msgs;
  for (Failure f : {roundTrip<device_state_t>(data), roundTrip<contact_t>(data), roundTrip<contact_batch_t>(data),
                    roundTrip<servo_stats_t>(data), roundTrip<subscribe_request_t>(data),
                    roundTrip<subscribe_reply_t>(data), roundTrip<heartbeat_t>(data), roundTrip<hello_t>(data),
                    roundTrip<client_force_t>(data), roundTrip<server_command_t>(data),
                    roundTrip<server_command_reply_t>(data), roundTrip<physics_poses_t>(data),
                    roundTrip<physics_impact_t>(data), roundTrip<physics_texel_t>(data),
                    roundTrip<physics_contacts_t>(data)})
    if (f) return f;
  return std::nullopt;
}

}  // namespace thx::fuzz::lcm_round_trip
