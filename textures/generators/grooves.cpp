// Parallel rounded U grooves running along y, one per period, centred in it.
//
// Across a groove, with s = |2t / width| for the distance t from its centre line,
//   h = -depth * (1 - s^4)^2   for s < 1, else 0.
// (1 - s^4)^2 has a flat-ish floor, steep walls and zero slope where it meets the plane, so the
// surface is smooth (C1) everywhere: no creases. Steepest wall slope = 2.42 * depth / (width/2)
// (at s^4 = 3/7), e.g. 50° for the defaults.
#include "textures/generators/common.hpp"

namespace thx::tex::gen {

namespace {

TextureMap makeGrooves(const Params& p, int size, std::uint64_t /*seed*/) {
  const double period = p.at("period"), width = p.at("width"), depth = p.at("depth");
  if (width > period) {
    failParams("grooves", "grooves wider than their period",
               "width=" + formatNumber(width) + ", period=" + formatNumber(period), "width <= period");
  }
  return rasterize(size, p.at("extent"), [&](double x, double /*y*/) {
    const double t = x - (std::floor(x / period) + 0.5) * period;
    const double s = std::fabs(2.0 * t / width);
    if (s >= 1.0) return SurfacePoint{};
    const double s3 = s * s * s, a = 1.0 - s3 * s;
    const double dh_ds = depth * 8.0 * a * s3;  // d/ds of -depth * a^2
    const double ds_dx = (t >= 0.0 ? 2.0 : -2.0) / width;
    return SurfacePoint{-depth * a * a, dh_ds * ds_dx, 0.0};
  });
}

}  // namespace

GeneratorEntry groovesGenerator() {
  return {{"grooves",
           "parallel rounded U grooves along y (smooth, no creases)",
           {
               {"period", 0.008, "m", "groove-to-groove distance along x", 1e-4, 10.0},
               {"width", 0.004, "m", "groove width at the plane", 1e-5, 10.0},
               {"depth", 0.001, "m", "groove depth", 1e-6, 0.1},
           }},
          makeGrooves};
}

}  // namespace thx::tex::gen
