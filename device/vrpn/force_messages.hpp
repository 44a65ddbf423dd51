#pragma once
// vrpn_ForceDevice messages (docs/vrpn.md §9). Same struct shape as base_messages.hpp. Client ->
// server messages use float32, server -> client reports float64, all big-endian.
//
// These are wire layouts only. What a PHANToM server does with the values (kspring as a fraction
// of the device maximum, the parameter clamps, d x 1000 to mm, the recovery rule) belongs to the
// device that renders them; decode() passes every value through unchanged.
#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "device/vrpn/byte_io.hpp"
#include "device/vrpn/error.hpp"

namespace thx::vrpn {

// Client -> server: plane a x + b y + c z + d = 0 (metres; free space where the expression is
// > 0; a (0,0,0) normal turns the plane off). Field order on the wire: plane[4], kspring, kdamp,
// fdyn, fstat, plane_index, n_rec_cycles. 40 bytes. Defaults are the stock base-class ones.
struct ForcePlane {
  static constexpr std::string_view kTypeName = "vrpn_ForceDevice Plane";
  static constexpr std::size_t kSize = 40;
  std::array<float, 4> plane{};
  float kspring = 0.8f;  // fraction of the device's maximum stiffness
  float kdamp = 0.001f;
  float fdyn = 0.3f;
  float fstat = 0.7f;
  std::int32_t plane_index = 0;  // the stock client always sends 0
  std::int32_t n_rec_cycles = 1;
  void encode(ByteWriter& w) const;
  static Result<ForcePlane> decode(std::span<const std::uint8_t> payload);
  bool operator==(const ForcePlane&) const = default;
};

// A stock client's startSurface() is one Plane message carrying its current plane, sendSurface()
// is Plane + Plane2, and stopSurface() is a Plane whose plane is (0,0,0,0): this one, with the
// other fields unchanged.
ForcePlane stopSurface(const ForcePlane& current);

// Client -> server: surface effects for plane 0 ("Plane2"), metres and Hz. 24 bytes.
struct ForcePlane2 {
  static constexpr std::string_view kTypeName = "vrpn_ForceDevice Plane2";
  static constexpr std::size_t kSize = 24;
  float k_adhesion_normal = 0.0f;
  float k_adhesion_lateral = 0.0f;
  float tex_amp = 0.0f;
  float tex_wavelength = 0.0f;
  float buzz_amp = 0.0f;
  float buzz_freq = 0.0f;
  void encode(ByteWriter& w) const;
  static Result<ForcePlane2> decode(std::span<const std::uint8_t> payload);
  bool operator==(const ForcePlane2&) const = default;
};

// Client -> server: F(x) = force + J (x - origin) within radius of origin (metres, newtons).
// jacobian is row-major, jacobian[i][j] = dF_i/dx_j. All zeros works as "stop". 64 bytes.
struct ForceField {
  static constexpr std::string_view kTypeName = "vrpn_ForceDevice Force_Field";
  static constexpr std::size_t kSize = 64;
  std::array<float, 3> origin{};
  std::array<float, 3> force{};
  std::array<std::array<float, 3>, 3> jacobian{};
  float radius = 0.0f;
  void encode(ByteWriter& w) const;
  static Result<ForceField> decode(std::span<const std::uint8_t> payload);
  bool operator==(const ForceField&) const = default;
};

// Client -> server: uint32 effect_id, uint32 n, float32 params[n]; 8 + 4n bytes, n bounded by the
// message size limit. Effect 0 = instant buzz (amplitude, frequency, duration[, direction x,y,z]);
// kStopEffect with no params stops it.
struct ForceCustomEffect {
  static constexpr std::string_view kTypeName = "vrpn_ForceDevice Custom Effect";
  static constexpr std::uint32_t kStopEffect = 0xFFFFFFFFu;
  std::uint32_t effect_id = 0;
  std::vector<float> params;
  void encode(ByteWriter& w) const;
  static Result<ForceCustomEffect> decode(std::span<const std::uint8_t> payload);
  bool operator==(const ForceCustomEffect&) const = default;
};

// Server -> client report: device force (newtons under HDAPI). 24 bytes.
struct ForceReport {
  static constexpr std::string_view kTypeName = "vrpn_ForceDevice Force";
  static constexpr std::size_t kSize = 24;
  std::array<double, 3> force{};
  void encode(ByteWriter& w) const;
  static Result<ForceReport> decode(std::span<const std::uint8_t> payload);
  bool operator==(const ForceReport&) const = default;
};

// Server -> client report: surface contact point (metres; stock sends an identity quaternion).
// 56 bytes.
struct ForceScp {
  static constexpr std::string_view kTypeName = "vrpn_ForceDevice SCP";
  static constexpr std::size_t kSize = 56;
  std::array<double, 3> pos{};
  std::array<double, 4> quat{0.0, 0.0, 0.0, 1.0};
  void encode(ByteWriter& w) const;
  static Result<ForceScp> decode(std::span<const std::uint8_t> payload);
  bool operator==(const ForceScp&) const = default;
};

// Server -> client: 0 value out of range, 1 duty cycle, 2 force/overheat, 3 misc. 4 bytes.
struct ForceError {
  static constexpr std::string_view kTypeName = "vrpn_ForceDevice Force_Error";
  static constexpr std::size_t kSize = 4;
  std::int32_t code = 0;
  void encode(ByteWriter& w) const;
  static Result<ForceError> decode(std::span<const std::uint8_t> payload);
  bool operator==(const ForceError&) const = default;
};

}  // namespace thx::vrpn
