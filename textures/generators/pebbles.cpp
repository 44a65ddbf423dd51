// Seeded pebbles: one ellipsoidal cap per cell of a square grid, standing on a flat ground.
//
// The grid has a whole number of cells across the extent (cell >= spacing), so the pattern tiles.
// Each pebble's semi-axes a >= b, orientation, height and centre offset are keyed by its cell;
// the centre moves only as far as keeps the whole ellipse inside its cell, so pebbles never
// overlap and a point only ever looks at its own cell.
//
// Shape: a spherical cap of base radius a and height H, stretched by b/a across its long axis:
//   rho^2 = (u/a)^2 + (v/b)^2,  eta = H/a,  R = (1 + eta^2) / (2 eta),
//   h = a * (sqrt(R^2 - rho^2) - (R - eta))     for rho < 1.
// The rim is a crease (the cap meets the ground at a finite slope). Requiring H <= b/2 keeps the
// steepest rim slope near 45-55°.
#include "textures/generators/common.hpp"

namespace thx::tex::gen {

namespace {

struct Pebble {
  double cx, cy;      // centre, plane coordinates
  double a, b;        // semi-axes, a >= b
  double cos_p, sin_p;  // orientation of the a axis
  double eta, r;      // cap shape in units of a
};

TextureMap makePebbles(const Params& p, int size, std::uint64_t seed) {
  const double extent = p.at("extent"), radius = p.at("radius"), radius_jitter = p.at("radius_jitter");
  const double elongation = p.at("elongation"), height = p.at("height");
  // Round the cell count down: cells never shrink below `spacing`, so parameters that fit at one
  // extent fit at every other.
  const auto n = std::max<std::int64_t>(1, std::int64_t(std::floor(extent / p.at("spacing") + 1e-9)));
  const double cell = extent / double(n);
  const double a_max = radius * (1.0 + radius_jitter);
  if (a_max > cell / 2.0) {
    failParams("pebbles", "pebbles do not fit their cells",
               "radius=" + formatNumber(radius) + ", radius_jitter=" + formatNumber(radius_jitter) +
                   ", cell=" + formatNumber(cell) + " (extent/" + std::to_string(n) + ")",
               "radius * (1 + radius_jitter) <= cell / 2");
  }
  const double b_min = radius * (1.0 - radius_jitter) * (1.0 - elongation);
  if (height > b_min / 2.0) {
    failParams("pebbles", "pebbles too tall for their narrowest width", "height=" + formatNumber(height),
               "height <= radius * (1 - radius_jitter) * (1 - elongation) / 2 = " + formatNumber(b_min / 2.0));
  }

  auto pebbleOf = [&](std::int64_t ci, std::int64_t cj) {
    auto rnd = [&](std::uint64_t salt) { return random01(seed, wrapIndex(ci, n), wrapIndex(cj, n), salt); };
    Pebble q{};
    q.a = radius * (1.0 + radius_jitter * (2.0 * rnd(1) - 1.0));
    q.b = q.a * (1.0 - elongation * rnd(2));
    const double phi = 2.0 * kPi * rnd(3);
    q.cos_p = std::cos(phi);
    q.sin_p = std::sin(phi);
    const double room = cell / 2.0 - q.a;  // >= 0 by the check above
    q.cx = (double(ci) + 0.5) * cell + room * (2.0 * rnd(4) - 1.0);
    q.cy = (double(cj) + 0.5) * cell + room * (2.0 * rnd(5) - 1.0);
    q.eta = height * (0.7 + 0.3 * rnd(6)) / q.a;
    q.r = (1.0 + q.eta * q.eta) / (2.0 * q.eta);
    return q;
  };

  return rasterize(size, extent, [&](double x, double y) {
    const Pebble q = pebbleOf(std::int64_t(std::floor(x / cell)), std::int64_t(std::floor(y / cell)));
    const double dx = x - q.cx, dy = y - q.cy;
    const double u = q.cos_p * dx + q.sin_p * dy, v = -q.sin_p * dx + q.cos_p * dy;
    const double rho2 = (u / q.a) * (u / q.a) + (v / q.b) * (v / q.b);
    if (rho2 >= 1.0) return SurfacePoint{};
    const double root = std::sqrt(q.r * q.r - rho2);
    const double h_u = -u / (q.a * root), h_v = -q.a * v / (q.b * q.b * root);
    return SurfacePoint{q.a * (root - (q.r - q.eta)), h_u * q.cos_p - h_v * q.sin_p, h_u * q.sin_p + h_v * q.cos_p};
  });
}

}  // namespace

GeneratorEntry pebblesGenerator() {
  return {{"pebbles",
           "seeded non-overlapping ellipsoidal pebble caps on a flat ground, one per grid cell",
           {
               {"spacing", 0.01, "m", "smallest grid cell size (grown to divide the extent)", 1e-4, 10.0},
               {"radius", 0.0038, "m", "mean long semi-axis", 1e-5, 5.0},
               {"radius_jitter", 0.25, "1", "seeded relative spread of the long semi-axis", 0.0, 0.9},
               {"elongation", 0.3, "1", "largest seeded shortening of the short semi-axis", 0.0, 0.9},
               {"height", 0.0009, "m", "largest cap height (seeded 70-100 % of it)", 1e-6, 1.0},
           }},
          makePebbles};
}

}  // namespace thx::tex::gen
