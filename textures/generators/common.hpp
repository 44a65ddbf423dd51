#pragma once
// Internal to the generators (not installed, not for other modules): what each generator file
// provides to the registry, and the helpers they share.
//
// Plane coordinates here are measured from the map's BOTTOM-LEFT corner: x = right, y = up, both
// in [0, extent). Texel (i, j) has its centre at x = (i + 0.5) * d, y = extent - (j + 0.5) * d with
// d = extent / size. Starting patterns at the corner makes a pattern whose period divides the
// extent tile seamlessly under Address::Wrap.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>

#include "textures/generators.hpp"
#include "textures/height_normals.hpp"
#include "textures/texture_error.hpp"

namespace thx::tex::gen {

inline constexpr double kPi = 3.14159265358979323846;

// Height (m, +up) and its exact gradient at one point of the plane.
struct SurfacePoint {
  double h = 0.0;
  double dhdx = 0.0;
  double dhdy = 0.0;
};

// Every parameter of the generator's spec, validated and with defaults filled in.
using Params = std::map<std::string, double>;

using MakeFn = TextureMap (*)(const Params& params, int size, std::uint64_t seed);

struct GeneratorEntry {
  GeneratorSpec spec;  // without `extent`: the registry adds it to every generator
  MakeFn make = nullptr;
};

GeneratorEntry bricksGenerator();
GeneratorEntry vvalleyGenerator();
GeneratorEntry groovesGenerator();
GeneratorEntry pebblesGenerator();
GeneratorEntry woodGenerator();
GeneratorEntry sineGenerator();
GeneratorEntry dimplesGenerator();
GeneratorEntry tiltedGenerator();
GeneratorEntry zigzagGenerator();
GeneratorEntry porcelainGenerator();
GeneratorEntry metalGenerator();
GeneratorEntry stoneGenerator();
GeneratorEntry ceramicTileGenerator();

std::string formatNumber(double v);

// A constraint between parameters failed (ranges of single parameters are checked by the registry).
[[noreturn]] void failParams(const std::string& kind, const std::string& problem, const std::string& value,
                             const std::string& expected);

// Deterministic randomness keyed by (seed, a, b, salt): a hash, so results do not depend on the
// order of evaluation or on the standard library. Returns a value in [0, 1).
inline std::uint64_t mix64(std::uint64_t z) {  // splitmix64 finaliser
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
inline double random01(std::uint64_t seed, std::int64_t a, std::int64_t b, std::uint64_t salt) {
  std::uint64_t h = mix64(seed);
  h = mix64(h ^ std::uint64_t(a));
  h = mix64(h ^ std::uint64_t(b));
  h = mix64(h ^ salt);
  return double(h >> 11) * 0x1.0p-53;
}
// Index modulo n, non-negative, so cell-keyed randomness repeats with the tile.
inline std::int64_t wrapIndex(std::int64_t k, std::int64_t n) {
  const std::int64_t m = k % n;
  return m < 0 ? m + n : m;
}
// Number of whole periods in the extent (at least 1), for keying randomness per tile.
inline std::int64_t periodsIn(double extent_m, double period_m) {
  return std::max<std::int64_t>(1, std::llround(extent_m / period_m));
}

// Builds the relief map of a continuous surface: depth = max(h) - h over the texel centres,
// normal = (-dh/dx, -dh/dy, 1) normalised, from the surface's own gradient (never from the grid).
// `surface(x, y)` returns a SurfacePoint. Two passes (range, then write) so no temporary of the
// map's size is needed.
template <class Surface>
TextureMap rasterize(int size, double extent_m, Surface&& surface) {
  const double d = extent_m / size;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int j = 0; j < size; ++j) {
    const double y = extent_m - (j + 0.5) * d;
    for (int i = 0; i < size; ++i) {
      const double h = surface((i + 0.5) * d, y).h;
      lo = std::min(lo, h);
      hi = std::max(hi, h);
    }
  }
  TextureMap map(size, size, Representation::Relief, std::max(hi - lo, kFlatReliefDepth_m));
  for (int j = 0; j < size; ++j) {
    const double y = extent_m - (j + 0.5) * d;
    for (int i = 0; i < size; ++i) {
      const SurfacePoint s = surface((i + 0.5) * d, y);
      map.setDepth(i, j, hi - s.h);
      // Normalise in double: slopes can be large, and setNormal's float normalisation would lose
      // the small components.
      const double inv_len = 1.0 / std::sqrt(s.dhdx * s.dhdx + s.dhdy * s.dhdy + 1.0);
      map.setNormal(i, j, Eigen::Vector3f(float(-s.dhdx * inv_len), float(-s.dhdy * inv_len), float(inv_len)));
    }
  }
  return map;
}

}  // namespace thx::tex::gen
