// Metal finishes, chosen by `pattern`: 0 brushed, 1 knurled, 2 hammered; every pattern carries the
// brushing scratches (scratch_depth = 0 turns them off).
//
// Brushed: fine scratches along x, one per band of height `scratch_spacing` (bands divide the
// extent). Each band's scratch sits at a seeded offset in the band's middle 60 %, has a seeded
// width (20-45 % of the band) and a raised-cosine profile across y, and its depth swells and fades
// along x, depth * (1 + sin(2 pi x / L + phi)) / 2 with seeded L (0.5-1.5 scratch_length) and phi,
// so scratches start and stop like real brushing marks. Anisotropic: slopes across x are much
// steeper than along it.
// Knurled: two sets of grooves crossing at +-45 degrees, h = -knurl_depth (q(x + y) + q(x - y)) / 2,
// q = ((1 - cos(2 pi t / P)) / 2)^2, P = knurl_pitch rounded to divide the extent: rounded pyramids.
// Hammered: one dent per cell of a jittered grid (`dent_spacing`), each a paraboloid bowl
// -dent_depth * k * (1 - r^2 / R^2) for r < R, seeded R (0.6-0.9 cell) and k (0.6-1); where dents
// overlap the deepest wins, so they meet in sharp ridges (creases), and the bowl rims are creases
// too. The sites stay in the middle 40 % of their cell, so R <= 0.9 cell never reaches beyond the
// 3 x 3 cells around the point.
#include "textures/generators/noise.hpp"

namespace thx::tex::gen {

namespace {

constexpr std::uint64_t kMetalSalt = 0x6d65746c;  // "metl"

SurfacePoint scratches(double x, double y, double band, std::int64_t bands, double length, double depth,
                       std::uint64_t seed) {
  const auto k = std::int64_t(std::floor(y / band));
  auto rnd = [&](std::uint64_t salt) { return random01(seed, wrapIndex(k, bands), 0, kMetalSalt + salt); };
  const double centre = (double(k) + 0.2 + 0.6 * rnd(1)) * band;
  const double half_width = band * (0.2 + 0.25 * rnd(2)) / 2.0;
  const double wavelength = length * (0.5 + rnd(3)), phase = 2.0 * kPi * rnd(4);
  const double arg = 2.0 * kPi * x / wavelength + phase;
  const double swell = 0.5 * (1.0 + std::sin(arg)), dswell = kPi / wavelength * std::cos(arg);
  const double dist = y - centre;
  if (std::fabs(dist) >= half_width) return {};
  const double c = 0.5 * (1.0 + std::cos(kPi * dist / half_width));
  const double dc = -0.5 * kPi / half_width * std::sin(kPi * dist / half_width);
  return {-depth * swell * c, -depth * dswell * c, -depth * swell * dc};
}

SurfacePoint knurl(double x, double y, double pitch, double depth) {
  SurfacePoint s;
  const double w = 2.0 * kPi / pitch;
  for (const double sign : {1.0, -1.0}) {
    const double arg = w * (x + sign * y);
    const double q = 0.5 * (1.0 - std::cos(arg));
    const double dq = q * std::sin(arg) * w;  // d(q^2)/dt = 2 q * sin(arg) * w / 2
    s.h -= depth * q * q / 2.0;
    s.dhdx -= depth * dq / 2.0;
    s.dhdy -= depth * sign * dq / 2.0;
  }
  return s;
}

// sizes: per dent cell, its radius and depth factors in [0, 1).
SurfacePoint dents(double x, double y, const VoronoiSites& sites, const Lattice& sizes, double depth) {
  SurfacePoint s;  // the undented sheet, h = 0, where no dent reaches
  const double cell = sites.cell();
  const auto i0 = std::int64_t(std::floor(x / cell)), j0 = std::int64_t(std::floor(y / cell));
  for (std::int64_t dj = -1; dj <= 1; ++dj)
    for (std::int64_t di = -1; di <= 1; ++di) {
      const std::int64_t ci = i0 + di, cj = j0 + dj;
      double cx, cy;
      sites.site(ci, cj, cx, cy);
      const double r_max = cell * (0.6 + 0.3 * sizes.value(ci, cj, 0));
      const double k = depth * (0.6 + 0.4 * sizes.value(ci, cj, 1));
      const double dx = x - cx, dy = y - cy;
      const double t = 1.0 - (dx * dx + dy * dy) / (r_max * r_max);
      // The deepest dent at the point wins: overlapping dents meet in sharp ridges, as hammer blows do.
      if (t <= 0.0 || -k * t >= s.h) continue;
      s = {-k * t, 2.0 * k * dx / (r_max * r_max), 2.0 * k * dy / (r_max * r_max)};
    }
  return s;
}

TextureMap makeMetal(const Params& p, int size, std::uint64_t seed) {
  const double extent = p.at("extent"), pattern = p.at("pattern");
  if (pattern != std::floor(pattern)) {
    failParams("metal", "pattern must be a whole number", "pattern=" + formatNumber(pattern),
               "0 (brushed), 1 (knurled) or 2 (hammered)");
  }
  const double spacing = p.at("scratch_spacing"), length = p.at("scratch_length"), sdepth = p.at("scratch_depth");
  const std::int64_t bands = periodsIn(extent, spacing);
  const double band = extent / double(bands);
  const double pitch = extent / double(periodsIn(extent, p.at("knurl_pitch"))), kdepth = p.at("knurl_depth");
  const int kind = int(pattern);
  // Dent sites and sizes, tabulated only for the hammered pattern.
  const std::int64_t dent_n = kind == 2 ? periodsIn(extent, p.at("dent_spacing")) : 1;
  const VoronoiSites dent_sites(extent / double(dent_n), dent_n, 0.4, seed, kMetalSalt + 32);
  const Lattice dent_sizes(dent_n, seed, kMetalSalt + 34);
  const double ddepth = p.at("dent_depth");
  return rasterize(size, extent, [&](double x, double y) {
    SurfacePoint s = sdepth > 0.0 ? scratches(x, y, band, bands, length, sdepth, seed) : SurfacePoint{};
    if (kind == 1) s += knurl(x, y, pitch, kdepth);
    if (kind == 2) s += dents(x, y, dent_sites, dent_sizes, ddepth);
    return s;
  });
}

}  // namespace

GeneratorEntry metalGenerator() {
  return {{"metal",
           "metal finishes: pattern 0 brushed (fine scratches along x), 1 knurled (crossed grooves), 2 hammered "
           "(overlapping dents); the scratches on every pattern",
           {
               {"pattern", 0, "1", "0 brushed, 1 knurled, 2 hammered", 0, 2},
               {"scratch_spacing", 0.002, "m", "one scratch per band of this height (grown to divide the extent)",
                1e-5, 1.0},
               {"scratch_length", 0.03, "m", "typical length over which a scratch swells and fades", 1e-4, 100.0},
               {"scratch_depth", 1.5e-5, "m", "deepest point of a scratch; 0 = no scratches", 0.0, 1e-3},
               {"knurl_pitch", 0.004, "m", "period of each groove set along x (pattern 1)", 1e-4, 1.0},
               {"knurl_depth", 0.0005, "m", "depth of the grooves (pattern 1)", 1e-6, 0.01},
               {"dent_spacing", 0.008, "m", "grid cell of the dents (pattern 2)", 1e-4, 1.0},
               {"dent_depth", 0.0003, "m", "depth of the deepest dent (pattern 2)", 1e-6, 0.01},
           }},
          makeMetal};
}

}  // namespace thx::tex::gen
