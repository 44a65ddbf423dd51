// A uniformly tilted plane: the analytic case for physics (a ball rolls with a = 5/7 g tan(angle)).
//
// The normal leans by angle_deg from +z towards the azimuth direction_deg (measured from +x
// towards +y): n = (sin a cos d, sin a sin d, cos a). The surface descends in that direction:
//   h = -tan(a) * (x cos d + y sin d).
// Does not tile (the depth ramps across the whole map).
#include "textures/generators/common.hpp"

namespace thx::tex::gen {

namespace {

TextureMap makeTilted(const Params& p, int size, std::uint64_t /*seed*/) {
  const double slope = std::tan(p.at("angle_deg") * kPi / 180.0);
  const double dir = p.at("direction_deg") * kPi / 180.0;
  const double gx = -slope * std::cos(dir), gy = -slope * std::sin(dir);
  return rasterize(size, p.at("extent"),
                   [&](double x, double y) { return SurfacePoint{gx * x + gy * y, gx, gy}; });
}

}  // namespace

GeneratorEntry tiltedGenerator() {
  return {{"tilted",
           "uniformly tilted plane: normal leans angle_deg towards azimuth direction_deg",
           {
               {"angle_deg", 10.0, "deg", "tilt of the normal from +z", 0.0, 80.0},
               {"direction_deg", 0.0, "deg", "azimuth of the downhill direction, from +x towards +y", -360.0, 360.0},
           }},
          makeTilted};
}

}  // namespace thx::tex::gen
