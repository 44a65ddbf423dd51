#pragma once
// Gaussian smoothing of a normal or relief map. Plain C++ in thx_textures (no OpenCV), so hapticd
// smooths a scene's texture at load time with the very code the tools and the stability map use:
// every program feels the same smoothed texels.
//
// Smoothing happens in the gradient domain. Each normal becomes the slope pair it encodes,
//   (sx, sy) = (-nx / nz, -ny / nz)   (= dh/dx, dh/dy of the surface, dimensionless),
// the slopes and, for relief maps, the depth are blurred with the SAME separable Gaussian, and
// the normals are rebuilt as (-sx, -sy, 1) / |.|. Why not blur the normals themselves: a blurred
// and renormalised normal is not the normal of any blurred surface, while blurring is linear and
// commutes with differencing, so a smoothed relief map's normals stay exactly as consistent with
// its smoothed depth as the input's were (and never less: an average of errors is no larger
// than the largest). Slopes are clamped to |s| <= max_slope first: a grazing normal (nz -> 0)
// encodes an unbounded slope that would otherwise swamp its neighbourhood.
//
// Borders: Address::Wrap reads taps across the edge from the other side (a tiling map stays
// seamless), Address::Clamp repeats the edge texel. Separable: along x, then along y.
// Kernel radius ceil(4 sigma) texels; sigma = 0 returns the map unchanged. Cost: O(texels x
// radius), about 2 x 17 multiply-adds per texel and channel at sigma = 2.
// maxDepth() is kept (a blurred depth stays inside the input's range) and so is the metadata;
// meta.params gains "smoothed sigma=<sigma> address=<wrap|clamp>".
#include "textures/sampling.hpp"
#include "textures/texture_map.hpp"

namespace thx::tex {

inline constexpr double kMaxSmoothingSigma = 256.0;  // texels

struct SmoothOptions {
  double sigma_texels = 1.0;  // in [0, kMaxSmoothingSigma]
  Address address = Address::Wrap;
  double max_slope = 50.0;  // |dh/dx|, |dh/dy| bound before blurring (50 = 88.9 deg)
};

// Throws TextureError on an empty map or a sigma / max_slope that is not finite or out of range.
TextureMap smoothTexture(const TextureMap& map, const SmoothOptions& options);

}  // namespace thx::tex
