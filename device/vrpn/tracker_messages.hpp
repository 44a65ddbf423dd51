#pragma once
// vrpn_Tracker messages we use (docs/vrpn.md §7). Metres, unit quaternions (x, y, z, w), float64
// big-endian. Same struct shape as base_messages.hpp.
//
// Reports start with int32 sensor and an int32 "pad" that stock senders fill with the sensor
// number again: we do the same on output and ignore it on input. A negative sensor is an error
// (the stock Remote drops the link).
#include <array>
#include <cstdint>
#include <span>
#include <string_view>

#include "device/vrpn/byte_io.hpp"
#include "device/vrpn/error.hpp"

namespace thx::vrpn {

// Server -> client, per report. 64 bytes.
struct TrackerPosQuat {
  static constexpr std::string_view kTypeName = "vrpn_Tracker Pos_Quat";
  static constexpr std::size_t kSize = 64;
  std::int32_t sensor = 0;
  std::array<double, 3> pos{};
  std::array<double, 4> quat{0.0, 0.0, 0.0, 1.0};
  void encode(ByteWriter& w) const;
  static Result<TrackerPosQuat> decode(std::span<const std::uint8_t> payload);
  bool operator==(const TrackerPosQuat&) const = default;
};

// Server -> client, per report: linear velocity (m/s) and the rotation over vel_quat_dt seconds.
// 72 bytes.
struct TrackerVelocity {
  static constexpr std::string_view kTypeName = "vrpn_Tracker Velocity";
  static constexpr std::size_t kSize = 72;
  std::int32_t sensor = 0;
  std::array<double, 3> vel{};
  std::array<double, 4> vel_quat{0.0, 0.0, 0.0, 1.0};
  double vel_quat_dt = 0.0;
  void encode(ByteWriter& w) const;
  static Result<TrackerVelocity> decode(std::span<const std::uint8_t> payload);
  bool operator==(const TrackerVelocity&) const = default;
};

// Client -> server: report rate in Hz. Exactly 8 bytes, else the stock server drops the link.
// The value is passed through unchecked; the server decides what rates it honours.
struct TrackerUpdateRate {
  static constexpr std::string_view kTypeName = "vrpn_Tracker set_update_rate";
  static constexpr std::size_t kSize = 8;
  double hz = 0.0;
  void encode(ByteWriter& w) const;
  static Result<TrackerUpdateRate> decode(std::span<const std::uint8_t> payload);
  bool operator==(const TrackerUpdateRate&) const = default;
};

// Client -> server: empty body.
struct TrackerResetOrigin {
  static constexpr std::string_view kTypeName = "vrpn_Tracker Reset_Origin";
  void encode(ByteWriter&) const {}
  static Result<TrackerResetOrigin> decode(std::span<const std::uint8_t> payload);
  bool operator==(const TrackerResetOrigin&) const = default;
};

}  // namespace thx::vrpn
