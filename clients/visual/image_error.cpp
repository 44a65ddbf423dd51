#include "clients/visual/image_error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace thx::visual {

ReferenceImage referenceImage(const tex::TexturedSurface& surface, const Camera& camera, int width, int height,
                              bool relief, const ReferenceLight& light) {
  ReferenceImage image{width, height, std::vector<std::optional<ReferenceHit>>(std::size_t(width) * height)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      image.hits[std::size_t(y) * width + x] = referenceHit(surface, camera.pixelRay(x, y), relief, light);
  return image;
}

PixelStats compareWithReference(const tex::TexturedSurface& surface, const ReferenceImage& reference,
                                const Rgba8Image& colour, const FloatImage& hits) {
  PixelStats stats;
  const int w = reference.width, h = reference.height;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      bool interior = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) interior = interior && reference.at(x + dx, y + dy).has_value();
      if (!interior) continue;
      const ReferenceHit& r = *reference.at(x, y);
      ++stats.compared;
      if (hits.at(x, y, 3) != 1.0f) ++stats.not_surface;
      const tex::TexelIndex gpu_texel =
          tex::texelOf(surface.map(), {hits.at(x, y, 0), hits.at(x, y, 1)}, surface.sampling().address);
      if (!(gpu_texel == r.texel)) ++stats.other_texel;
      const int expected = int(std::lround(255.0 * std::min(1.0, r.intensity)));
      const int error = std::abs(int(colour.at(x, y, 0)) - expected);
      stats.sum_error += error;
      stats.max_error = std::max(stats.max_error, error);
    }
  return stats;
}

}  // namespace thx::visual
