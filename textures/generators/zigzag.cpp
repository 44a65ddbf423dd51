// A street: one rounded channel whose centre line zig-zags across the texture while it runs
// along x (tilt the surface in the scene to make it run downhill).
//
// Centre line (plane coordinates, origin at the texture's centre)
// y_c(x) = amplitude * asin(a sin(2πx/period)) / asin(a): a zig-zag (triangle wave) with rounded
// bends (a = sharpness in (0, 1): near 0 a sine, near 1 straight diagonal legs and tight bends).
// Across the
// channel, with s = |2 (y - y_c(x)) / width|, the profile of `grooves`:
//   h = -depth * (1 - s^4)^2   for s < 1, else 0,
// smooth (C1) everywhere, so rolling objects meet no creases. The offset is measured along y, not
// perpendicular to the centre line: the walls are a little steeper on the diagonal legs.
#include <cmath>
#include <numbers>

#include "textures/generators/common.hpp"

namespace thx::tex::gen {

namespace {

TextureMap makeZigzag(const Params& p, int size, std::uint64_t /*seed*/) {
  const double period = p.at("period"), amplitude = p.at("amplitude"), width = p.at("width"),
               depth = p.at("depth"), a = p.at("sharpness");
  const double w = 2.0 * std::numbers::pi / period;
  const double norm = 1.0 / std::asin(a);
  const double half = 0.5 * p.at("extent");
  // Centred on the texture (the plane's frame origin): the street crosses y = 0 at x = 0.
  return rasterize(size, p.at("extent"), [&](double x_corner, double y_corner) {
    const double x = x_corner - half, y = y_corner - half;
    const double sn = std::sin(w * x);
    const double yc = amplitude * norm * std::asin(a * sn);
    const double dyc_dx = amplitude * norm * a * std::cos(w * x) * w / std::sqrt(1.0 - a * a * sn * sn);
    const double t = y - yc;
    const double s = std::fabs(2.0 * t / width);
    if (s >= 1.0) return SurfacePoint{};
    const double s3 = s * s * s, q = 1.0 - s3 * s;
    const double dh_ds = depth * 8.0 * q * s3;  // d/ds of -depth * q^2
    const double ds_dt = (t >= 0.0 ? 2.0 : -2.0) / width;
    return SurfacePoint{-depth * q * q, dh_ds * ds_dt * -dyc_dx, dh_ds * ds_dt};
  });
}

}  // namespace

GeneratorEntry zigzagGenerator() {
  return {{"zigzag",
           "a rounded street channel zig-zagging across while it runs along x (smooth, no creases)",
           {
               {"period", 0.1, "m", "length along x of one zig and one zag", 1e-3, 100.0},
               {"amplitude", 0.03, "m", "how far the centre line swings to each side", 0.0, 10.0},
               {"width", 0.04, "m", "channel width at the plane", 1e-4, 10.0},
               {"depth", 0.004, "m", "channel depth", 1e-6, 0.1},
               {"sharpness", 0.95, "1", "bend sharpness (near 0: a sine; near 1: straight legs, tight bends)", 0.01,
                0.999},
           }},
          makeZigzag};
}

}  // namespace thx::tex::gen
