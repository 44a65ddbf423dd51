#include "textures/texture_fingerprint.hpp"

#include <cstdio>

#include "base/fnv1a64.hpp"

namespace thx::tex {

std::uint64_t textureFingerprint(const TexturedSurface& surface) {
  const TextureMap& map = surface.map();
  const PlaneMapping& mapping = surface.mapping();
  const bool relief = surface.usesRelief();
  Fnv1a64 h;
  h.tag("thx.texture.v1");
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
