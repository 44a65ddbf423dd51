#include "device/vrpn/force_messages.hpp"

#include <algorithm>
#include <string>
#include <type_traits>

#include "device/vrpn/limits.hpp"
#include "device/vrpn/payload_size.hpp"

namespace thx::vrpn {

namespace {

template <class T, std::size_t N>
void putAll(ByteWriter& w, const std::array<T, N>& v) {
  for (T x : v) {
    if constexpr (std::is_same_v<T, float>)
      w.f32(x);
    else
      w.f64(x);
  }
}

template <class T, std::size_t N>
void getAll(ByteReader& r, std::array<T, N>& v) {
  for (T& x : v) {
    if constexpr (std::is_same_v<T, float>)
      x = r.f32();
    else
      x = r.f64();
  }
}

}  // namespace

void ForcePlane::encode(ByteWriter& w) const {
  putAll(w, plane);
  w.f32(kspring);
  w.f32(kdamp);
  w.f32(fdyn);
  w.f32(fstat);
  w.i32(plane_index);
  w.i32(n_rec_cycles);
}

Result<ForcePlane> ForcePlane::decode(std::span<const std::uint8_t> payload) {
  if (auto e = checkSize(kTypeName, payload, kSize)) return *e;
  ByteReader r(payload);
  ForcePlane m;
  getAll(r, m.plane);
  m.kspring = r.f32();
  m.kdamp = r.f32();
  m.fdyn = r.f32();
  m.fstat = r.f32();
  m.plane_index = r.i32();
  m.n_rec_cycles = r.i32();
  return m;
}

ForcePlane stopSurface(const ForcePlane& current) {
  ForcePlane p = current;
  p.plane = {0.0f, 0.0f, 0.0f, 0.0f};
  return p;
}

void ForcePlane2::encode(ByteWriter& w) const {
  w.f32(k_adhesion_normal);
  w.f32(k_adhesion_lateral);
  w.f32(tex_amp);
  w.f32(tex_wavelength);
  w.f32(buzz_amp);
  w.f32(buzz_freq);
}

Result<ForcePlane2> ForcePlane2::decode(std::span<const std::uint8_t> payload) {
  if (auto e = checkSize(kTypeName, payload, kSize)) return *e;
  ByteReader r(payload);
  ForcePlane2 m;
  m.k_adhesion_normal = r.f32();
  m.k_adhesion_lateral = r.f32();
  m.tex_amp = r.f32();
  m.tex_wavelength = r.f32();
  m.buzz_amp = r.f32();
  m.buzz_freq = r.f32();
  return m;
}

void ForceField::encode(ByteWriter& w) const {
  putAll(w, origin);
  putAll(w, force);
  for (const auto& row : jacobian) putAll(w, row);
  w.f32(radius);
}

Result<ForceField> ForceField::decode(std::span<const std::uint8_t> payload) {
  if (auto e = checkSize(kTypeName, payload, kSize)) return *e;
  ByteReader r(payload);
  ForceField m;
  getAll(r, m.origin);
  getAll(r, m.force);
  for (auto& row : m.jacobian) getAll(r, row);
  m.radius = r.f32();
  return m;
}

namespace {
// The most params one message can carry within kMaxPayloadLength.
constexpr std::size_t kMaxCustomParams = (kMaxPayloadLength - 8) / 4;
}  // namespace

void ForceCustomEffect::encode(ByteWriter& w) const {
  const std::size_t n = std::min(params.size(), kMaxCustomParams);
  w.u32(effect_id);
  w.u32(std::uint32_t(n));
  for (std::size_t i = 0; i < n; ++i) w.f32(params[i]);
}

Result<ForceCustomEffect> ForceCustomEffect::decode(std::span<const std::uint8_t> payload) {
  if (payload.size() < 8)
    return sizeError(kTypeName, payload.size(), "at least 8");
  ByteReader r(payload);
  ForceCustomEffect m;
  m.effect_id = r.u32();
  const std::uint32_t n = r.u32();
  // Compare in the payload's terms so a huge n can neither overflow nor size an allocation.
  if ((payload.size() - 8) % 4 != 0 || (payload.size() - 8) / 4 != n)
    return Error{ErrorCode::kPayloadSize, std::string(kTypeName) + " with " + std::to_string(n) + " params in a " +
                                              std::to_string(payload.size()) + "-byte body"};
  m.params.resize(n);
  for (float& p : m.params) p = r.f32();
  return m;
}

void ForceReport::encode(ByteWriter& w) const { putAll(w, force); }

Result<ForceReport> ForceReport::decode(std::span<const std::uint8_t> payload) {
  if (auto e = checkSize(kTypeName, payload, kSize)) return *e;
  ByteReader r(payload);
  ForceReport m;
  getAll(r, m.force);
  return m;
}

void ForceScp::encode(ByteWriter& w) const {
  putAll(w, pos);
  putAll(w, quat);
}

Result<ForceScp> ForceScp::decode(std::span<const std::uint8_t> payload) {
  if (auto e = checkSize(kTypeName, payload, kSize)) return *e;
  ByteReader r(payload);
  ForceScp m;
  getAll(r, m.pos);
  getAll(r, m.quat);
  return m;
}

void ForceError::encode(ByteWriter& w) const { w.i32(code); }

Result<ForceError> ForceError::decode(std::span<const std::uint8_t> payload) {
  if (auto e = checkSize(kTypeName, payload, kSize)) return *e;
  ByteReader r(payload);
  return ForceError{r.i32()};
}

}  // namespace thx::vrpn
