#include "textures/texture_fingerprint.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>

namespace thx::tex {

namespace {

class Fnv1a64 {
 public:
  void byte(std::uint8_t b) {
    h_ ^= b;
    h_ *= 0x100000001b3ULL;
  }
  template <class UInt>
  void le(UInt v) {  // little-endian, whatever the host
    for (std::size_t k = 0; k < sizeof(UInt); ++k) byte(std::uint8_t(v >> (8 * k)));
  }
  void i16(std::int16_t v) { le(std::uint16_t(v)); }
  void i32(std::int32_t v) { le(std::uint32_t(v)); }
  // Geometry in units of 1e-12 (picometres for lengths); non-finite values hash as INT64_MIN.
  void quantised(double v) {
    const double scaled = v * 1e12;
    le(std::uint64_t(std::isfinite(scaled) && std::fabs(scaled) < 9e18 ? std::llround(scaled) : INT64_MIN));
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

}  // namespace

std::uint64_t textureFingerprint(const TexturedSurface& surface) {
  const TextureMap& map = surface.map();
  const PlaneMapping& mapping = surface.mapping();
  const bool relief = surface.usesRelief();
  Fnv1a64 h;
  char tag[16] = {};
  std::memcpy(tag, "thx.texture.v1", 14);
  for (char c : tag) h.byte(std::uint8_t(c));
  h.i32(map.width());
  h.i32(map.height());
  h.byte(relief ? 1 : 0);
  h.byte(surface.sampling().filter == Filter::Nearest ? 0 : 1);
  h.byte(surface.sampling().address == Address::Wrap ? 0 : 1);
  h.quantised(mapping.size_m.x());
  h.quantised(mapping.size_m.y());
  const Eigen::Matrix3d r = mapping.plane_to_world.linear();
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) h.quantised(r(row, col));
  for (int k = 0; k < 3; ++k) h.quantised(mapping.plane_to_world.translation()(k));
  h.quantised(relief ? map.maxDepth() : 0.0);
  for (int j = 0; j < map.height(); ++j)
    for (int i = 0; i < map.width(); ++i) {
      h.i16(map.normalCodeX(i, j));
      h.i16(map.normalCodeY(i, j));
      if (relief) h.le(map.depthCode(i, j));
    }
  return h.value();
}

std::string formatFingerprint(std::uint64_t fingerprint) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "0x%016llx", static_cast<unsigned long long>(fingerprint));
  return buf;
}

}  // namespace thx::tex
