#pragma once
// Fields the tracker messages share (tracker_messages.*, tracker_transform_messages.*): runs of
// big-endian f64s and the sensor number's check.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "device/vrpn/byte_io.hpp"
#include "device/vrpn/error.hpp"

namespace thx::vrpn {

template <std::size_t N>
void putAll(ByteWriter& w, const std::array<double, N>& v) {
  for (double x : v) w.f64(x);
}

template <std::size_t N>
void getAll(ByteReader& r, std::array<double, N>& v) {
  for (double& x : v) x = r.f64();
}

inline std::optional<Error> checkSensor(std::string_view type_name, std::int32_t sensor) {
  if (sensor >= 0) return std::nullopt;
  return Error{ErrorCode::kBadValue, std::string(type_name) + " with negative sensor " + std::to_string(sensor)};
}

}  // namespace thx::vrpn
