// Wood grain: the growth rings of a log cut by the plank's plane, warped by smooth noise.
//
// The tree axis runs roughly along x below the surface, at seeded lateral position cy, depth z0
// and small seeded tilts (ky, kz). A point's ring coordinate is its distance to that axis plus a
// warp,
//   rho = sqrt((y - cy - ky x)^2 + (z0 + kz x)^2) + warp(x, y),
// and the late-wood grooves are narrow dips at every ring:
//   h = -depth * ((1 - cos(2 pi rho / ring_spacing)) / 2)^3.
// The warp is a sum of seeded sinusoids (wavelengths 0.6-1.4 x warp_wavelength, random
// directions and phases) with r.m.s. about `warp`: smooth noise whose gradient is exact.
// Everything is smooth, so the map has no creases; it does not tile.
#include <array>

#include "textures/generators/common.hpp"

namespace thx::tex::gen {

namespace {

constexpr int kWaves = 6;

struct Wave {
  double kx, ky, phase, amplitude;
};

TextureMap makeWood(const Params& p, int size, std::uint64_t seed) {
  const double extent = p.at("extent"), spacing = p.at("ring_spacing"), depth = p.at("depth");
  const double warp = p.at("warp"), wavelength = p.at("warp_wavelength");
  auto rnd = [&](std::int64_t k) { return random01(seed, k, 0, 0x776f6f64 /* "wood" */); };

  const double cy = extent * (0.2 + 0.6 * rnd(0));
  const double z0 = extent * (0.3 + 0.7 * rnd(1));
  const double ky = 0.15 * (2.0 * rnd(2) - 1.0);
  const double kz = 0.1 * (2.0 * rnd(3) - 1.0);  // |kz x| <= 0.1 extent < z0: axis stays below
  std::array<Wave, kWaves> waves{};
  for (int w = 0; w < kWaves; ++w) {
    const double k = 2.0 * kPi / (wavelength * (0.6 + 0.8 * rnd(10 + 3 * w)));
    const double dir = 2.0 * kPi * rnd(11 + 3 * w);
    // Amplitude sqrt(2 / kWaves) gives the sum an r.m.s. of 1.
    waves[std::size_t(w)] = {k * std::cos(dir), k * std::sin(dir), 2.0 * kPi * rnd(12 + 3 * w),
                             warp * std::sqrt(2.0 / kWaves)};
  }
  const double to_phase = 2.0 * kPi / spacing;

  return rasterize(size, extent, [&](double x, double y) {
    const double ly = y - cy - ky * x, lz = z0 + kz * x;
    const double dist = std::sqrt(ly * ly + lz * lz);
    double rho = dist;
    double drho_dx = (-ky * ly + kz * lz) / dist, drho_dy = ly / dist;
    for (const Wave& w : waves) {
      const double arg = w.kx * x + w.ky * y + w.phase;
      rho += w.amplitude * std::sin(arg);
      const double c = w.amplitude * std::cos(arg);
      drho_dx += c * w.kx;
      drho_dy += c * w.ky;
    }
    const double phase = to_phase * rho;
    const double g = 0.5 * (1.0 - std::cos(phase));
    const double dh_drho = -depth * 3.0 * g * g * 0.5 * std::sin(phase) * to_phase;
    return SurfacePoint{-depth * g * g * g, dh_drho * drho_dx, dh_drho * drho_dy};
  });
}

}  // namespace

GeneratorEntry woodGenerator() {
  return {{"wood",
           "seeded wood grain: warped growth rings with narrow grooves (smooth, does not tile)",
           {
               {"ring_spacing", 0.003, "m", "distance between growth rings", 1e-4, 1.0},
               {"depth", 0.0003, "m", "depth of the groove at each ring", 1e-6, 0.01},
               {"warp", 0.0015, "m", "r.m.s. displacement of the rings by the noise", 0.0, 1.0},
               {"warp_wavelength", 0.04, "m", "typical wavelength of the noise", 1e-3, 100.0},
           }},
          makeWood};
}

}  // namespace thx::tex::gen
