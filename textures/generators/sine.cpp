// Sinusoidal bumps: an egg-crate of smooth bumps and dips,
//   h = amplitude * sin(2 pi x / period) * sin(2 pi y / period).
// Smooth everywhere (no creases); tiles when the period divides the extent.
#include "textures/generators/common.hpp"

namespace thx::tex::gen {

namespace {

TextureMap makeSine(const Params& p, int size, std::uint64_t /*seed*/) {
  const double amplitude = p.at("amplitude"), k = 2.0 * kPi / p.at("period");
  return rasterize(size, p.at("extent"), [&](double x, double y) {
    const double sx = std::sin(k * x), cx = std::cos(k * x), sy = std::sin(k * y), cy = std::cos(k * y);
    return SurfacePoint{amplitude * sx * sy, amplitude * k * cx * sy, amplitude * k * sx * cy};
  });
}

}  // namespace

GeneratorEntry sineGenerator() {
  return {{"sine",
           "sinusoidal bumps: amplitude * sin(2 pi x / period) * sin(2 pi y / period)",
           {
               {"amplitude", 0.0005, "m", "bump height above the mid plane", 1e-7, 0.1},
               {"period", 0.01, "m", "wavelength along x and y", 1e-4, 10.0},
           }},
          makeSine};
}

}  // namespace thx::tex::gen
