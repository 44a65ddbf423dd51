#include "server/tools/stability_map_valley.hpp"

#include <cmath>
#include <numbers>

#include "textures/generators.hpp"
#include "textures/smoothing.hpp"

namespace thx::srv::stab {

double ValleyGeometry::floorXM() const {
  // Generator x runs from the map's left edge; local x = generator x - extent / 2. Floors sit at
  // generator x = (k + 1/2) period: take the first one at or right of the centre.
  const double half = extentM() / 2.0;
  const double k = std::ceil(half / period_m - 0.5);
  return (k + 0.5) * period_m - half;
}

ValleyMap buildValleyMap(double angle_deg, bool smoothed, const ValleyGeometry& g) {
  tex::GenerateRequest request;
  request.kind = "vvalley";
  request.size = g.sizeTexels();
  request.params = {{"angle_deg", angle_deg}, {"period", g.period_m}, {"extent", g.extentM()}};
  tex::TextureMap map = tex::generate(request);
  if (smoothed) {
    tex::SmoothOptions options;
    options.sigma_texels = g.smoothing_sigma_texels;
    options.address = tex::Address::Wrap;  // the map tiles; so does its blur
    map = tex::smoothTexture(map, options);
  }
  ValleyMap v;
  v.angle_deg = angle_deg;
  v.smoothed = smoothed;
  v.wall_angle_deg = 90.0 - angle_deg / 2.0;
  v.depth_m = g.period_m / 2.0 * std::tan(v.wall_angle_deg * std::numbers::pi / 180.0);
  v.map = std::make_shared<const tex::TextureMap>(std::move(map));
  return v;
}

}  // namespace thx::srv::stab
