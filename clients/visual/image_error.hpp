#pragma once
// A rendered frame against the CPU reference (cpu_reference.hpp), pixel by pixel: the fraction of
// pixels whose hit lands on another texel than the reference's, and the intensity error in 8-bit
// LSB of the red channel (the references' lighting: white albedo, no ambient, no specular).
// Pixels next to the map's border or the background are skipped (partial coverage there).
#include <optional>
#include <vector>

#include "clients/visual/cpu_reference.hpp"
#include "clients/visual/framebuffer.hpp"

namespace thx::visual {

struct ReferenceImage {
  int width = 0, height = 0;
  std::vector<std::optional<ReferenceHit>> hits;  // row-major, top row first
  const std::optional<ReferenceHit>& at(int x, int y) const { return hits[std::size_t(y) * width + x]; }
};

ReferenceImage referenceImage(const tex::TexturedSurface& surface, const Camera& camera, int width, int height,
                              bool relief, const ReferenceLight& light);

struct PixelStats {
  int compared = 0;
  int other_texel = 0;    // GPU hit on another texel than the reference's
  int not_surface = 0;    // the reference sees the surface, the frame does not
  double sum_error = 0;   // |GPU - reference| in 8-bit LSB
  int max_error = 0;
  double otherTexelFraction() const { return compared ? double(other_texel) / compared : 1.0; }
  double meanError() const { return compared ? sum_error / compared : 1e9; }
};

// `hits` is the frame's hit buffer (Framebuffer::readHits).
PixelStats compareWithReference(const tex::TexturedSurface& surface, const ReferenceImage& reference,
                                const Rgba8Image& colour, const FloatImage& hits);

}  // namespace thx::visual
