// Parallel V-shaped valleys running along y: the haptic crease test case (docs/design.md §5).
//
// Ridges at x = k * period, floors half way between. The two walls of a valley meet at the
// floor with the opening angle theta, so each wall rises at alpha = 90° - theta/2 from the plane
// and the valley depth follows: depth = (period / 2) * tan(alpha). A wall descending towards +x
// has the normal (sin alpha, 0, cos alpha). Ridges and floors are creases (no defined normal);
// a texel centre exactly on one takes the wall to its right.
#include "textures/generators/common.hpp"

namespace thx::tex::gen {

namespace {

TextureMap makeVValley(const Params& p, int size, std::uint64_t /*seed*/) {
  const double period = p.at("period");
  const double alpha = (90.0 - p.at("angle_deg") / 2.0) * kPi / 180.0;
  const double slope = std::tan(alpha);

  TextureMap map = rasterize(size, p.at("extent"), [&](double x, double /*y*/) {
    const double f = x / period - std::floor(x / period);  // position within the period, [0, 1)
    if (f < 0.5) return SurfacePoint{-slope * f * period, -slope, 0.0};
    return SurfacePoint{-slope * (1.0 - f) * period, slope, 0.0};
  });
  map.meta().params = "depth=" + formatNumber(slope * period / 2.0) + " (derived)";
  return map;
}

}  // namespace

GeneratorEntry vvalleyGenerator() {
  return {{"vvalley",
           "parallel V valleys along y; depth = period/2 * tan(90deg - angle_deg/2)",
           {
               {"angle_deg", 90.0, "deg", "opening angle between the two walls of a valley", 10.0, 170.0},
               {"period", 0.004, "m", "ridge-to-ridge distance along x", 1e-4, 10.0},
           }},
          makeVValley};
}

}  // namespace thx::tex::gen
