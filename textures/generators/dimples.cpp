// Spherical-cap dimples on a square grid (centres at ((k + 1/2) spacing, (l + 1/2) spacing)).
//
// A dimple of rim radius a and depth d is a cap of the sphere of radius R = (a^2 + d^2) / (2 d):
//   h = -(sqrt(R^2 - r^2) - (R - d))   for r < a, else 0.
// The rim is a crease; the rim slope a / (R - d) stays finite because d <= 0.9 a (84° at most).
// radius <= spacing / 2 keeps each dimple inside its own cell.
#include "textures/generators/common.hpp"

namespace thx::tex::gen {

namespace {

TextureMap makeDimples(const Params& p, int size, std::uint64_t /*seed*/) {
  const double spacing = p.at("spacing"), a = p.at("radius"), d = p.at("depth");
  if (a > spacing / 2.0) {
    failParams("dimples", "dimples overlap",
               "radius=" + formatNumber(a) + ", spacing=" + formatNumber(spacing), "radius <= spacing / 2");
  }
  if (d > 0.9 * a) {
    failParams("dimples", "dimple too deep for its radius",
               "depth=" + formatNumber(d) + ", radius=" + formatNumber(a), "depth <= 0.9 * radius");
  }
  const double big_r = (a * a + d * d) / (2.0 * d);
  return rasterize(size, p.at("extent"), [&](double x, double y) {
    const double dx = x - (std::floor(x / spacing) + 0.5) * spacing;
    const double dy = y - (std::floor(y / spacing) + 0.5) * spacing;
    const double r2 = dx * dx + dy * dy;
    if (r2 >= a * a) return SurfacePoint{};
    const double root = std::sqrt(big_r * big_r - r2);
    return SurfacePoint{-(root - (big_r - d)), dx / root, dy / root};
  });
}

}  // namespace

GeneratorEntry dimplesGenerator() {
  return {{"dimples",
           "spherical-cap dimples on a square grid",
           {
               {"spacing", 0.01, "m", "grid pitch along x and y", 1e-4, 10.0},
               {"radius", 0.003, "m", "rim radius of a dimple", 1e-5, 5.0},
               {"depth", 0.001, "m", "depth of a dimple at its centre", 1e-6, 1.0},
           }},
          makeDimples};
}

}  // namespace thx::tex::gen
