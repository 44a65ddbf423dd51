#pragma once
// The vrpn_Tracker transform and workspace messages a stock vrpn_Phantom answers (docs/vrpn.md §7,
// §9 "the tracker transform requests"). A client asks with an empty request; the server replies
// with the matching message. Metres, quaternions (x, y, z, w), float64 big-endian; exact sizes
// (a wrong size drops the link at a stock Remote, §4). Same struct shape as tracker_messages.hpp.
#include <array>
#include <cstdint>
#include <span>
#include <string_view>

#include "device/vrpn/byte_io.hpp"
#include "device/vrpn/error.hpp"

namespace thx::vrpn {

// Server -> client: the tracker frame in the room frame. 56 bytes: f64 pos[3], f64 quat[4].
struct TrackerToRoom {
  static constexpr std::string_view kTypeName = "vrpn_Tracker To_Room";
  static constexpr std::size_t kSize = 56;
  std::array<double, 3> pos{};
  std::array<double, 4> quat{0.0, 0.0, 0.0, 1.0};
  void encode(ByteWriter& w) const;
  static Result<TrackerToRoom> decode(std::span<const std::uint8_t> payload);
  bool operator==(const TrackerToRoom&) const = default;
};

// Server -> client: one sensor's unit-to-sensor transform. 64 bytes: i32 sensor, i32 0 (the pad
// is zero here, unlike the reports' pad), f64 pos[3], f64 quat[4]. A negative sensor is an error.
struct TrackerUnitToSensor {
  static constexpr std::string_view kTypeName = "vrpn_Tracker Unit_To_Sensor";
  static constexpr std::size_t kSize = 64;
  std::int32_t sensor = 0;
  std::array<double, 3> pos{};
  std::array<double, 4> quat{0.0, 0.0, 0.0, 1.0};
  void encode(ByteWriter& w) const;
  static Result<TrackerUnitToSensor> decode(std::span<const std::uint8_t> payload);
  bool operator==(const TrackerUnitToSensor&) const = default;
};

// Server -> client: the tracker's working volume as a box. 48 bytes: f64 min[3], f64 max[3].
struct TrackerWorkspace {
  static constexpr std::string_view kTypeName = "vrpn_Tracker Workspace";
  static constexpr std::size_t kSize = 48;
  std::array<double, 3> min{};
  std::array<double, 3> max{};
  void encode(ByteWriter& w) const;
  static Result<TrackerWorkspace> decode(std::span<const std::uint8_t> payload);
  bool operator==(const TrackerWorkspace&) const = default;
};

// Client -> server requests: empty bodies.
struct TrackerRequestToRoom {
  static constexpr std::string_view kTypeName = "vrpn_Tracker Request_Tracker_To_Room";
  void encode(ByteWriter&) const {}
  static Result<TrackerRequestToRoom> decode(std::span<const std::uint8_t> payload);
  bool operator==(const TrackerRequestToRoom&) const = default;
};

struct TrackerRequestUnitToSensor {
  static constexpr std::string_view kTypeName = "vrpn_Tracker Request_Unit_To_Sensor";
  void encode(ByteWriter&) const {}
  static Result<TrackerRequestUnitToSensor> decode(std::span<const std::uint8_t> payload);
  bool operator==(const TrackerRequestUnitToSensor&) const = default;
};

struct TrackerRequestWorkspace {
  static constexpr std::string_view kTypeName = "vrpn_Tracker Request_Tracker_Workspace";
  void encode(ByteWriter&) const {}
  static Result<TrackerRequestWorkspace> decode(std::span<const std::uint8_t> payload);
  bool operator==(const TrackerRequestWorkspace&) const = default;
};

}  // namespace thx::vrpn
