// Bricks in running bond: flat brick faces at seeded heights, joined by rounded mortar troughs.
//
// A brick cell is brick_length x brick_height (centre to centre, joint included); every other
// course is shifted by half a brick. With s = distance from the point to its cell's boundary
// (the joint's centre line), the surface within half a mortar width of the boundary follows a
// raised-cosine trough
//   c(s) = (1 + cos(pi * s / w)) / 2,  w = mortar / 2,   h = top * (1 - c) - mortar_depth * c,
// which is flat (zero slope) both on the joint line and where it meets the brick face. Both sides
// of a joint measure s to the same line, so h is continuous; its gradient has creases where the
// bed and head joints meet and across the diagonal of a joint corner.
#include "textures/generators/common.hpp"

namespace thx::tex::gen {

namespace {

TextureMap makeBricks(const Params& p, int size, std::uint64_t seed) {
  const double length = p.at("brick_length"), height = p.at("brick_height");
  const double mortar = p.at("mortar"), depth = p.at("mortar_depth"), jitter = p.at("jitter");
  const double extent = p.at("extent");
  if (mortar >= std::min(length, height)) {
    failParams("bricks", "mortar joint wider than a brick",
               "mortar=" + formatNumber(mortar) + ", brick_length=" + formatNumber(length) +
                   ", brick_height=" + formatNumber(height),
               "mortar < min(brick_length, brick_height)");
  }
  if (jitter >= depth) {
    failParams("bricks", "brick height jitter reaches the mortar floor",
               "jitter=" + formatNumber(jitter) + ", mortar_depth=" + formatNumber(depth), "jitter < mortar_depth");
  }
  const std::int64_t cols = periodsIn(extent, length), rows = periodsIn(extent, height);
  const double w = mortar / 2.0;

  return rasterize(size, extent, [&](double x, double y) {
    const double row_f = std::floor(y / height);
    const auto row = std::int64_t(row_f);
    const double shift = (row % 2 != 0) ? length / 2.0 : 0.0;
    const double col_f = std::floor((x - shift) / length);
    const auto col = std::int64_t(col_f);
    const double u = x - shift - (col_f + 0.5) * length;  // from the brick's centre
    const double v = y - (row_f + 0.5) * height;
    const double top = jitter * (2.0 * random01(seed, wrapIndex(col, cols), wrapIndex(row, rows), 0) - 1.0);

    const double du = length / 2.0 - std::fabs(u), dv = height / 2.0 - std::fabs(v);
    const double s = std::min(du, dv);
    if (s >= w) return SurfacePoint{top, 0.0, 0.0};
    const double c = 0.5 * (1.0 + std::cos(kPi * s / w));
    const double dc_ds = -0.5 * kPi / w * std::sin(kPi * s / w);
    const double dh_ds = -(top + depth) * dc_ds;
    // s shrinks as the point moves away from the brick's centre.
    const double ds_dx = du < dv ? (u > 0.0 ? -1.0 : 1.0) : 0.0;
    const double ds_dy = du < dv ? 0.0 : (v > 0.0 ? -1.0 : 1.0);
    return SurfacePoint{top * (1.0 - c) - depth * c, dh_ds * ds_dx, dh_ds * ds_dy};
  });
}

}  // namespace

GeneratorEntry bricksGenerator() {
  return {{"bricks",
           "running-bond brick wall: rounded mortar joints, seeded per-brick height jitter",
           {
               {"brick_length", 0.04, "m", "brick pitch along x, joint included", 1e-4, 10.0},
               {"brick_height", 0.02, "m", "course pitch along y, joint included", 1e-4, 10.0},
               {"mortar", 0.003, "m", "mortar joint width", 1e-5, 1.0},
               {"mortar_depth", 0.0015, "m", "depth of the joint below a brick face", 1e-6, 0.1},
               {"jitter", 0.00015, "m", "seeded per-brick height offset, +/- this", 0.0, 0.1},
           }},
          makeBricks};
}

}  // namespace thx::tex::gen
