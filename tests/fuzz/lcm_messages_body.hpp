#pragma once
// One fuzzing step for the LCM messages hapticd takes from the network (THX_SUBSCRIBE,
// THX_HEARTBEAT, THX_COMMAND, THX_CLIENT_FORCE: server/receiver.hpp, subscription_inbox.hpp),
// shared by the libFuzzer target (libfuzzer/lcm_messages.cpp) and the short run in `make test`
// (test_fuzz_lcm_messages.cpp). Returns the first broken property, or nothing; memory errors and
// UB are left to ASan/UBSan.
//
// Input: byte 0 picks the channel (mod 4), the rest is the datagram's payload.
// Properties:
//  1. decodeUntrusted (the receiver's decode) refuses with a message naming the type, or accepts
//     bytes that the generated encoder writes back exactly (encode . decode = identity);
//  2. try_decode of every thx_msgs type on the same bytes: what decodes re-encodes to the bytes
//     it consumed (so no type loses or invents content, e.g. at an embedded NUL);
//  3. our checks after the decode: a subscription reply is either a refusal with a reason or a
//     grant on exactly stream_channel(stream, batch, client_id); every reply hapticd would send
//     encodes, decodes back equal and stays small whatever the request's size; a heartbeat counts
//     only for a subscribed client; a command reaches the scene loader only with a valid scene
//     name; an accepted client force has valid ids and a finite force within the limit, and is
//     what the table sums.
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <thx_msgs/protocol.hpp>
#include <vector>

#include "scenes/scene_lookup.hpp"
#include "server/client_force_table.hpp"
#include "server/server_commands.hpp"
#include "server/subscriptions.hpp"
#include "server/untrusted_input.hpp"
#include "tests/fuzz/lcm_round_trip.hpp"

namespace thx::fuzz::lcm_messages {

using Failure = std::optional<std::string>;
using Bytes = std::vector<std::uint8_t>;
using lcm_round_trip::encoded;

inline constexpr const char* kChannels[] = {thx_msgs::kChannelSubscribe, thx_msgs::kChannelHeartbeat,
                                            thx_msgs::kChannelCommand, thx_msgs::kChannelClientForce};
// The largest reply hapticd may send, whatever the request's size: replies quote at most a
// shortened form of what they refuse.
inline constexpr int kMaxReplyBytes = 1024;
inline constexpr double kMaxForceN = 10.0;

// A reply hapticd would publish: it must be a message its clients can decode, of bounded size.
template <class R>
Failure sendable(const R& reply, const char* what) {
  const Bytes b = encoded(reply);
  if (b.size() > std::size_t(kMaxReplyBytes))
    return std::string(what) + ": reply of " + std::to_string(b.size()) + " bytes";
  R back;
  if (thx_msgs::try_decode(b.data(), b.size(), back) != int(b.size()) || encoded(back) != b)
    return std::string(what) + ": the reply does not decode back to itself";
  return std::nullopt;
}

// Property 1: the receiver's decode. `ok` says whether it accepted.
template <class T>
Failure untrusted(std::span<const std::uint8_t> data, T& m, bool& ok) {
  const std::string problem = srv::decodeUntrusted(data.data(), data.size(), m);
  ok = problem.empty();
  if (!ok) {
    if (problem.find(T::getTypeName()) == std::string::npos)
      return std::string("refusal does not name the type ") + T::getTypeName() + ": " + problem;
    return std::nullopt;
  }
  if (encoded(m) != Bytes(data.begin(), data.end()))
    return std::string(T::getTypeName()) + ": accepted bytes do not re-encode to themselves";
  return std::nullopt;
}

inline Failure subscribe(std::span<const std::uint8_t> data) {
  thx_msgs::subscribe_request_t req;
  bool ok = false;
  if (Failure f = untrusted(data, req, ok); f || !ok) return f;
  srv::SubscriptionTable table{srv::SubscriptionLimits{}};
  const thx_msgs::subscribe_reply_t reply = table.handleRequest(req, 0);
  if (Failure f = sendable(reply, "subscribe_reply_t")) return f;
  if (!reply.accepted) {
    if (reply.reason.empty()) return std::string("subscription refused without a reason");
    if (table.numClients() != 0) return std::string("a refused subscription left a client behind");
    return std::nullopt;
  }
  if (req.action != thx_msgs::subscribe_request_t::ACTION_SUBSCRIBE) return std::nullopt;  // an unsubscribe
  const std::string expect = thx_msgs::stream_channel(req.stream, req.batch != 0, req.client_id);
  if (expect.empty() || reply.channel != expect)
    return "subscription granted on '" + reply.channel + "', expected '" + expect + "'";
  if (reply.channel.size() > thx_msgs::kMaxChannelLength) return std::string("granted channel longer than LCM allows");
  thx_msgs::heartbeat_t hb{};
  hb.client_id = req.client_id;
  if (!table.heartbeat(hb, 1)) return std::string("the granted client's heartbeat was not counted");
  return std::nullopt;
}

inline Failure heartbeat(std::span<const std::uint8_t> data) {
  thx_msgs::heartbeat_t hb;
  bool ok = false;
  if (Failure f = untrusted(data, hb, ok); f || !ok) return f;
  srv::SubscriptionTable table{srv::SubscriptionLimits{}};
  thx_msgs::subscribe_request_t req{};
  req.client_id = "fuzz";
  req.stream = std::string(thx_msgs::kStreamServoStats);
  req.action = thx_msgs::subscribe_request_t::ACTION_SUBSCRIBE;
  req.rate_hz = 1.0;
  if (!table.handleRequest(req, 0).accepted) return std::string("the fixed subscription was refused");
  if (table.heartbeat(hb, 1) != (hb.client_id == "fuzz"))
    return "heartbeat from '" + hb.client_id + "' counted against client 'fuzz' wrongly";
  return std::nullopt;
}

// Records what reaches the loader and starts nothing.
struct RecordingLoads : srv::SceneLoads {
  std::vector<std::string> begun;
  std::optional<std::string> begin(const std::string& name) override {
    begun.push_back(name);
    return "not loaded in the fuzz run";
  }
  std::optional<Outcome> poll() override { return std::nullopt; }
};

inline Failure command(std::span<const std::uint8_t> data) {
  thx_msgs::server_command_t cmd;
  bool ok = false;
  if (Failure f = untrusted(data, cmd, ok); f || !ok) return f;
  rt::LatestSlot<srv::FaultReset> slot;
  RecordingLoads loads;
  srv::ServerCommands commands(&slot, 1, &loads);
  const std::optional<thx_msgs::server_command_reply_t> reply = commands.handle(cmd);
  for (const std::string& name : loads.begun)
    if (!scene::isValidSceneName(name) || name.find('/') != std::string::npos || name.front() == '.')
      return "the scene loader was asked for '" + name + "'";
  if (!reply) {  // waits for the servo: only a reset by a valid client does
    if (cmd.action != thx_msgs::server_command_t::ACTION_RESET_FAULTS || !thx_msgs::is_valid_client_id(cmd.client_id))
      return "command " + std::to_string(cmd.action) + " from '" + cmd.client_id + "' left unanswered";
    return std::nullopt;
  }
  if (Failure f = sendable(*reply, "server_command_reply_t")) return f;
  if (reply->accepted || reply->reason.empty()) return std::string("an immediate reply must be a refusal with a reason");
  if (reply->client_id != cmd.client_id && reply->client_id != "?")
    return "reply echoes client '" + reply->client_id + "' for '" + cmd.client_id + "'";
  return std::nullopt;
}

inline Failure clientForce(std::span<const std::uint8_t> data) {
  thx_msgs::client_force_t m;
  bool ok = false;
  if (Failure f = untrusted(data, m, ok); f || !ok) return f;
  srv::ClientForceTable table(kMaxForceN, 100'000'000);
  if (!table.accept(m, 0)) return std::nullopt;
  if (!thx_msgs::is_valid_client_id(m.client_id) || !thx_msgs::is_valid_source_tag(m.source))
    return "client force accepted from '" + m.client_id + "'/'" + m.source + "'";
  const Eigen::Vector3d f(m.f_world[0], m.f_world[1], m.f_world[2]);
  if (!f.allFinite() || f.norm() > kMaxForceN) return std::string("client force accepted outside the limit");
  if (table.sum(0) != f) return std::string("the table's sum is not the one accepted force");
  return std::nullopt;
}

inline Failure fuzzOnce(std::span<const std::uint8_t> input) {
  if (input.empty()) return std::nullopt;
  const std::span<const std::uint8_t> data = input.subspan(1);
  if (Failure f = lcm_round_trip::everyType(data)) return f;
  switch (input[0] % 4) {
    case 0: return subscribe(data);
    case 1: return heartbeat(data);
    case 2: return command(data);
    default: return clientForce(data);
  }
}

}  // namespace thx::fuzz::lcm_messages
