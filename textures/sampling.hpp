#pragma once
// Sampling a TextureMap: the one convention every modality uses (docs/design.md §4 rule 4).
//
//  (u, v) in [0, 1)^2: u grows to the image right (+x), v grows to the image TOP (+y).
//  Texel (i, j) covers u in [i/W, (i+1)/W) and v in (1-(j+1)/H, 1-j/H]; its centre is at
//    u = (i + 0.5) / W,  v = 1 - (j + 0.5) / H.
//  Nearest returns the texel that contains (u, v); bilinear interpolates between the four
//  nearest texel centres and renormalises the normal. Depth is interpolated, not renormalised.
//  Address::Wrap repeats the map; Address::Clamp extends the edge texels outward.
//  Non-finite (u, v) never reaches an integer conversion: it samples as the flat plane
//  (normal (0,0,1), depth 0) so a bad device reading cannot cause undefined behaviour.
//
// Real-time safe: no allocation, no locks, no system calls (except texelsOnSegment, which
// returns a vector). Callers of the walk: the physics client's texel paths (walkCells); the
// servo does not walk texels.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <vector>

#include "textures/texture_map.hpp"

namespace thx::tex {

enum class Filter { Nearest, Bilinear };
enum class Address { Wrap, Clamp };

struct SampleOptions {
  Filter filter = Filter::Bilinear;
  Address address = Address::Wrap;
};

struct TexCoord {
  double u = 0.0;
  double v = 0.0;
};

struct Sample {
  Eigen::Vector3f normal{0.0f, 0.0f, 1.0f};  // tangent frame, unit length
  float depth = 0.0f;                        // metres into the surface (0 for normal maps)
};

// Resolves a possibly out-of-range texel index along one axis of n texels.
inline int resolveIndex(long long k, int n, Address address) {
  if (address == Address::Clamp) return k < 0 ? 0 : (k >= n ? n - 1 : int(k));
  long long m = k % n;
  return int(m < 0 ? m + n : m);
}

// Continuous texel coordinates: s along columns, t along rows, texel centres at integers.
inline double texelS(const TextureMap& map, double u) { return u * map.width() - 0.5; }
inline double texelT(const TextureMap& map, double v) { return (1.0 - v) * map.height() - 0.5; }

TexCoord texelCentre(const TextureMap& map, TexelIndex t);
// The texel containing (u, v), after wrap/clamp.
TexelIndex texelOf(const TextureMap& map, TexCoord uv, Address address);

// A sample read in two parts: where it lies first (its texels and their weights), then its depth,
// and its normal only where it is wanted, each as sample() reads it, to the bit. The physics reads a
// textured object's depth at every texel under it and its normal only where that texel is a
// contact candidate (a grooved block: 4,200 depths and 1,600 normals a step).
class SamplePlace {
 public:
  // The four texels round a place and their weights (bilinear; texel centres at half-integers).
  struct Bilinear {
    int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
    float w00 = 0, w10 = 0, w01 = 0, w11 = 0;
  };
  SamplePlace() = default;  // the flat plane's sample (as a non-finite uv's)
  SamplePlace(const TextureMap& map, TexCoord uv, const SampleOptions& options);
  float depth() const;
  Eigen::Vector3f normal() const;

 private:
  const TextureMap* map_ = nullptr;
  bool finite_ = false, nearest_ = false;
  Bilinear texels_;  // nearest: (i0, j0) alone
};

Sample sample(const TextureMap& map, TexCoord uv, const SampleOptions& options);
inline Eigen::Vector3f sampleNormal(const TextureMap& map, TexCoord uv, const SampleOptions& options) {
  return sample(map, uv, options).normal;
}
// The depth alone, as sample() reads it to the bit, without the normal (a third of the work).
float sampleDepth(const TextureMap& map, TexCoord uv, const SampleOptions& options);

// Every cell of the UNWRAPPED texel grid the segment a->b crosses, in order from a (column
// floor(u W), row floor((1 - v) H): TexturedSurface::texelContaining's indices, no wrap/clamp).
// `visit(long long i, long long j, double t_enter)` gets the segment parameter in [0, 1] at which
// the segment enters the cell (0 for the first); it returns false to stop. The traversal steps
// one axis at a time, so it yields exactly 1 + |di| + |dj| cells. Returns the cells visited.
// This is the walk a moving contact uses to report every texel it crosses between two steps.
template <class Visit>
std::size_t walkCells(const TextureMap& map, TexCoord a, TexCoord b, Visit&& visit);

// Every texel the segment a->b crosses, in order from a, each listed once per visit
// (Amanatides-Woo traversal on the unwrapped grid, then wrap/clamp; consecutive repeats that
// clamping creates are merged). A segment inside one texel yields that texel. The traversal
// always steps one axis at a time, so a segment crossing |di| columns and |dj| rows yields
// exactly 1 + |di| + |dj| cells on the unwrapped grid.
// `visit(TexelIndex)` returns false to stop early. Returns the number of texels visited.
// `max_texels` bounds the work for absurd inputs (a stop counts as truncation).
template <class Visit>
std::size_t walkTexels(const TextureMap& map, TexCoord a, TexCoord b, Address address, Visit&& visit,
                       std::size_t max_texels = std::size_t(1) << 22);

std::vector<TexelIndex> texelsOnSegment(const TextureMap& map, TexCoord a, TexCoord b, Address address,
                                        std::size_t max_texels = std::size_t(1) << 22);

// ---------------------------------------------------------------------------------------------

template <class Visit>
std::size_t walkCells(const TextureMap& map, TexCoord a, TexCoord b, Visit&& visit) {
  if (!std::isfinite(a.u) || !std::isfinite(a.v) || !std::isfinite(b.u) || !std::isfinite(b.v)) return 0;
  // Cell space: x = column coordinate, y = row coordinate; cell = floor.
  const double x0 = a.u * map.width(), y0 = (1.0 - a.v) * map.height();
  const double x1 = b.u * map.width(), y1 = (1.0 - b.v) * map.height();
  constexpr double kLimit = 1e15;  // keeps llround/floor in range; beyond this nothing is sensible
  if (std::fabs(x0) > kLimit || std::fabs(y0) > kLimit || std::fabs(x1) > kLimit || std::fabs(y1) > kLimit) return 0;

  long long cx = (long long)std::floor(x0), cy = (long long)std::floor(y0);
  const long long ex = (long long)std::floor(x1), ey = (long long)std::floor(y1);
  const double dx = x1 - x0, dy = y1 - y0;
  const int step_x = dx > 0 ? 1 : (dx < 0 ? -1 : 0);
  const int step_y = dy > 0 ? 1 : (dy < 0 ? -1 : 0);
  constexpr double kInf = 1e300;
  // Parameter t in [0,1] along the segment at which the next vertical / horizontal grid line is hit.
  double t_max_x = step_x > 0 ? ((double)(cx + 1) - x0) / dx : (step_x < 0 ? ((double)cx - x0) / dx : kInf);
  double t_max_y = step_y > 0 ? ((double)(cy + 1) - y0) / dy : (step_y < 0 ? ((double)cy - y0) / dy : kInf);
  const double t_delta_x = step_x != 0 ? 1.0 / std::fabs(dx) : kInf;
  const double t_delta_y = step_y != 0 ? 1.0 / std::fabs(dy) : kInf;
  const long long total = (ex - cx) * step_x + (ey - cy) * step_y;  // steps still to take

  double t_enter = 0.0;
  std::size_t visited = 0;
  for (long long k = 0; k <= total; ++k) {
    ++visited;
    if (!visit(cx, cy, std::fmin(1.0, std::fmax(0.0, t_enter)))) return visited;
    if (k == total) break;
    // Step the axis whose grid line comes first; the remaining-step budget decides ties and
    // guards against rounding so we finish exactly on the end cell.
    const bool x_left = cx != ex, y_left = cy != ey;
    if (x_left && (!y_left || t_max_x < t_max_y)) {
      cx += step_x;
      t_enter = t_max_x;
      t_max_x += t_delta_x;
    } else {
      cy += step_y;
      t_enter = t_max_y;
      t_max_y += t_delta_y;
    }
  }
  return visited;
}

template <class Visit>
std::size_t walkTexels(const TextureMap& map, TexCoord a, TexCoord b, Address address, Visit&& visit,
                       std::size_t max_texels) {
  // Wrap: shift both ends by whole periods so the integer cells stay small.
  if (address == Address::Wrap && std::isfinite(a.u) && std::isfinite(a.v)) {
    const double du = std::floor(a.u), dv = std::floor(a.v);
    a.u -= du; b.u -= du;
    a.v -= dv; b.v -= dv;
  }
  std::size_t visited = 0;
  TexelIndex last{-1, -1};
  walkCells(map, a, b, [&](long long i, long long j, double) {
    const TexelIndex cell{resolveIndex(i, map.width(), address), resolveIndex(j, map.height(), address)};
    if (cell == last) return true;  // clamping repeats the edge texel: merged
    if (visited >= max_texels) return false;
    ++visited;
    last = cell;
    return bool(visit(cell));
  });
  return visited;
}

}  // namespace thx::tex
