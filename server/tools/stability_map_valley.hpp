#pragma once
// The V-valley texture of one map column: generated once per (opening angle, smoothing) and shared
// read-only by every cell that uses it.
//
// Geometry (textures/generators/vvalley.cpp): valleys run along y, ridges at generator
// x = k * period, floors half way between. The map spans `periods` whole periods, so it tiles
// under Address::Wrap, and the period is a whole number of texels, so every floor lies exactly on
// a texel boundary: bilinear sampling then turns the normal over one texel, symmetric about the
// floor, the same in every valley and for every angle.
#include <memory>

#include "textures/texture_map.hpp"

namespace thx::srv::stab {

struct ValleyGeometry {
  double period_m = 0.004;     // ridge to ridge, as scenes/vvalley.yaml
  int texels_per_period = 20;  // 0.2 mm texels (vvalley.yaml: 0.195 mm)
  int periods = 10;            // the map is periods * period wide (0.04 m)
  double smoothing_sigma_texels = 2.0;  // the "normal smoothing" mitigation (gradient domain)

  double extentM() const { return period_m * periods; }
  int sizeTexels() const { return texels_per_period * periods; }
  double texelM() const { return period_m / texels_per_period; }
  // Plane-local x of the valley floor nearest the plane's centre (the map is centred on the origin).
  double floorXM() const;
};

struct ValleyMap {
  double angle_deg = 0.0;
  bool smoothed = false;
  double wall_angle_deg = 0.0;  // alpha = 90 - angle / 2: the walls' rise from the plane
  double depth_m = 0.0;         // analytic valley depth, period / 2 * tan(alpha)
  std::shared_ptr<const tex::TextureMap> map;  // relief; read as a normal map by choice
};

// Throws tex::TextureError for an opening angle outside the generator's range [10, 170] deg.
ValleyMap buildValleyMap(double angle_deg, bool smoothed, const ValleyGeometry& geometry);

}  // namespace thx::srv::stab
