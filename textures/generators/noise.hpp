#pragma once
// Internal to the generators: seeded smooth noise and cell networks with exact gradients, shared
// by porcelain, stone, ceramic_tile and metal. Everything is keyed by (seed, lattice index, salt)
// through random01, and every lattice wraps with the tile, so a pattern whose cell divides the
// extent tiles seamlessly. The per-point random values are tabulated once per map (the search
// below visits 50 sites per texel; hashing each visit made a 512² map take seconds), except for
// lattices too fine to be worth a table, which hash on the fly with the same result.
#include <vector>

#include "textures/generators/common.hpp"

namespace thx::tex::gen {

inline SurfacePoint& operator+=(SurfacePoint& a, const SurfacePoint& b) {
  a.h += b.h;
  a.dhdx += b.dhdx;
  a.dhdy += b.dhdy;
  return a;
}

// Lattices up to this many points per side are tabulated (16 MiB for a Lattice); finer ones hash.
inline constexpr std::int64_t kMaxTabulated = 1024;

// Two seeded values in [0, 1) per point of an n x n lattice that repeats every n points.
class Lattice {
 public:
  Lattice(std::int64_t n, std::uint64_t seed, std::uint64_t salt) : n_(n), seed_(seed), salt_(salt) {
    if (n_ > kMaxTabulated) return;
    table_.resize(std::size_t(2 * n_ * n_));
    for (std::int64_t i = 0; i < n_; ++i)
      for (std::int64_t j = 0; j < n_; ++j) {
        table_[std::size_t(2 * (i * n_ + j))] = random01(seed_, i, j, salt_);
        table_[std::size_t(2 * (i * n_ + j) + 1)] = random01(seed_, i, j, salt_ + 1);
      }
  }
  std::int64_t n() const { return n_; }
  // The k-th (0 or 1) value of lattice point (i, j), any integers (wrapped).
  double value(std::int64_t i, std::int64_t j, int k) const {
    const std::int64_t wi = wrapIndex(i, n_), wj = wrapIndex(j, n_);
    if (table_.empty()) return random01(seed_, wi, wj, salt_ + std::uint64_t(k));
    return table_[std::size_t(2 * (wi * n_ + wj) + k)];
  }

 private:
  std::int64_t n_;
  std::uint64_t seed_, salt_;
  std::vector<double> table_;
};

// Perlin gradient noise on a square lattice of cell `cell` (metres) that repeats every n cells:
// unit gradients keyed per lattice point, quintic fade. Value roughly in [-0.7, 0.7], C2-smooth.
class GradientNoise {
 public:
  GradientNoise(double cell, std::int64_t n, std::uint64_t seed, std::uint64_t salt)
      : cell_(cell), angles_(n, seed, salt) {
    if (n > kMaxTabulated) return;
    directions_.resize(std::size_t(2 * n * n));
    for (std::int64_t i = 0; i < n; ++i)
      for (std::int64_t j = 0; j < n; ++j) {
        const double a = 2.0 * kPi * angles_.value(i, j, 0);
        directions_[std::size_t(2 * (i * n + j))] = std::cos(a);
        directions_[std::size_t(2 * (i * n + j) + 1)] = std::sin(a);
      }
  }

  SurfacePoint operator()(double x, double y) const {
    const double gx = x / cell_, gy = y / cell_;
    const double fxl = std::floor(gx), fyl = std::floor(gy);
    const auto ix = std::int64_t(fxl), iy = std::int64_t(fyl);
    const double fx = gx - fxl, fy = gy - fyl;
    double g[4][2];  // gradients at (0,0), (1,0), (0,1), (1,1)
    for (int k = 0; k < 4; ++k) direction(ix + (k & 1), iy + (k >> 1), g[k]);
    const double a = g[0][0] * fx + g[0][1] * fy, b = g[1][0] * (fx - 1) + g[1][1] * fy;
    const double c = g[2][0] * fx + g[2][1] * (fy - 1), d = g[3][0] * (fx - 1) + g[3][1] * (fy - 1);
    const double u = fade(fx), v = fade(fy), du = dfade(fx), dv = dfade(fy);
    const double k = a - b - c + d;
    double grad[2];
    for (int axis = 0; axis < 2; ++axis) {
      const double gk = g[0][axis] - g[1][axis] - g[2][axis] + g[3][axis];
      grad[axis] = g[0][axis] + u * (g[1][axis] - g[0][axis]) + v * (g[2][axis] - g[0][axis]) + u * v * gk;
    }
    grad[0] += du * ((b - a) + v * k);
    grad[1] += dv * ((c - a) + u * k);
    return {a + u * (b - a) + v * (c - a) + u * v * k, grad[0] / cell_, grad[1] / cell_};
  }

 private:
  // The unit gradient at lattice point (i, j), from the table when there is one.
  void direction(std::int64_t i, std::int64_t j, double g[2]) const {
    if (directions_.empty()) {
      const double a = 2.0 * kPi * angles_.value(i, j, 0);
      g[0] = std::cos(a);
      g[1] = std::sin(a);
      return;
    }
    const std::int64_t n = angles_.n(), k = 2 * (wrapIndex(i, n) * n + wrapIndex(j, n));
    g[0] = directions_[std::size_t(k)];
    g[1] = directions_[std::size_t(k + 1)];
  }
  static double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
  static double dfade(double t) { return 30 * t * t * (t * (t - 2) + 1); }
  double cell_;
  Lattice angles_;
  std::vector<double> directions_;  // cos, sin per lattice point
};

// Fractal sum of gradient noise: octave o has wavelength base / 2^o (rounded so it divides the
// extent) and amplitude amplitude * gain^o. Octaves shorter than three texels (min_wavelength)
// are left out: on the grid they would only alias.
class FractalNoise {
 public:
  FractalNoise(double extent, double base, int octaves, double amplitude, double gain, double min_wavelength,
               std::uint64_t seed, std::uint64_t salt) {
    double wavelength = base, amp = amplitude;
    for (int o = 0; o < octaves; ++o, wavelength /= 2.0, amp *= gain) {
      const std::int64_t n = periodsIn(extent, wavelength);
      const double cell = extent / double(n);
      if (cell < min_wavelength) break;
      octaves_.push_back({amp, GradientNoise(cell, n, seed, salt + 2 * std::uint64_t(o))});
    }
  }
  SurfacePoint operator()(double x, double y) const {
    SurfacePoint s;
    for (const Octave& o : octaves_) {
      const SurfacePoint q = o.noise(x, y);
      s += SurfacePoint{o.amplitude * q.h, o.amplitude * q.dhdx, o.amplitude * q.dhdy};
    }
    return s;
  }

 private:
  struct Octave {
    double amplitude;
    GradientNoise noise;
  };
  std::vector<Octave> octaves_;
};

// A jittered-grid Voronoi network: one seeded site per cell of side `cell` (n cells per period),
// each within the middle `jitter` of its cell.
//
// border(x, y): the distance from a point to the border of its Voronoi cell and its gradient (sites
// within the middle 90 % of their cells at most). The
// distance to the border with a neighbour's cell is the distance to the bisector of the two
// sites, linear in the point, so its gradient is the unit vector between the sites; the nearest
// border wins (a crease where two borders are equally near).
struct CellBorder {
  double s = 0.0;                // metres to the nearest border
  double dsdx = 0.0, dsdy = 0.0;
};

class VoronoiSites {
 public:
  VoronoiSites(double cell, std::int64_t n, double jitter, std::uint64_t seed, std::uint64_t salt)
      : cell_(cell), jitter_(jitter), offsets_(n, seed, salt) {}

  double cell() const { return cell_; }
  std::int64_t n() const { return offsets_.n(); }
  // The site of cell (ci, cj), any integers, in plane coordinates.
  void site(std::int64_t ci, std::int64_t cj, double& x, double& y) const {
    x = (double(ci) + 0.5 + jitter_ * (offsets_.value(ci, cj, 0) - 0.5)) * cell_;
    y = (double(cj) + 0.5 + jitter_ * (offsets_.value(ci, cj, 1) - 0.5)) * cell_;
  }

  // Exact wherever the distance is below a quarter cell, which is all a crack (narrower than half a
  // cell) needs: the 5 x 5 cells around the point hold its nearest site (sites stay in the middle
  // 90 % of their cells, so that one is within 1.34 cells) and every site whose border comes
  // nearer than 0.35 cells (a site beyond them is at least 2.05 cells away, and the distance to
  // a border is at least half the difference of the distances to the two sites).
  CellBorder border(double x, double y) const {
    const auto i0 = std::int64_t(std::floor(x / cell_)), j0 = std::int64_t(std::floor(y / cell_));
    double sx[25], sy[25];
    int nearest = 0;
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 25; ++k) {
      site(i0 + k % 5 - 2, j0 + k / 5 - 2, sx[k], sy[k]);
      const double d2 = (x - sx[k]) * (x - sx[k]) + (y - sy[k]) * (y - sy[k]);
      if (d2 < best) {
        best = d2;
        nearest = k;
      }
    }
    const double nx = sx[nearest], ny = sy[nearest];
    CellBorder out;
    out.s = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 25; ++k) {
      if (k == nearest) continue;
      const double ax = sx[k] - nx, ay = sy[k] - ny, len = std::sqrt(ax * ax + ay * ay);
      const double s = ((sx[k] * sx[k] + sy[k] * sy[k]) - (nx * nx + ny * ny) - 2.0 * (x * ax + y * ay)) / (2.0 * len);
      if (s < out.s) out = {s, -ax / len, -ay / len};
    }
    return out;
  }

 private:
  double cell_, jitter_;
  Lattice offsets_;
};

// A groove of half-width w and depth `depth` along a line at distance s (gradient ds) from the
// point: raised-cosine profile, flat on the line and where it meets the surface around it.
inline SurfacePoint grooveAt(const CellBorder& b, double w, double depth) {
  if (b.s >= w || depth <= 0.0) return {};
  const double c = 0.5 * (1.0 + std::cos(kPi * b.s / w));
  const double dc = -0.5 * kPi / w * std::sin(kPi * b.s / w);
  return {-depth * c, -depth * dc * b.dsdx, -depth * dc * b.dsdy};
}

// Fractal noise cut by raised-cosine cracks along the borders of a Voronoi network: the relief of
// porcelain (faint undulation, crazing) and of stone (roughness, cleft planes) alike.
struct CrackedNoise {
  double extent = 0.0;
  double wavelength = 0.0, amplitude = 0.0, gain = 0.5;  // FractalNoise's first octave and ratio
  int octaves = 1;
  double min_wavelength = 0.0;                  // three texels
  double crack_cell_request = 0.0;              // grown or shrunk to divide the extent
  double jitter = 0.8;                          // of the Voronoi sites
  double crack_width = 0.0, crack_depth = 0.0;  // depth 0: no cracks
  std::uint64_t seed = 0, salt = 0;
};

inline TextureMap rasterizeCrackedNoise(int size, const CrackedNoise& c) {
  const FractalNoise noise(c.extent, c.wavelength, c.octaves, c.amplitude, c.gain, c.min_wavelength, c.seed, c.salt);
  const std::int64_t n = periodsIn(c.extent, c.crack_cell_request);
  // The site table is only built when there are cracks to draw.
  const VoronoiSites sites(c.extent / double(n), c.crack_depth > 0.0 ? n : 1, c.jitter, c.seed, c.salt + 1000);
  return rasterize(size, c.extent, [&](double x, double y) {
    SurfacePoint s = noise(x, y);
    if (c.crack_depth > 0.0) s += grooveAt(sites.border(x, y), c.crack_width / 2.0, c.crack_depth);
    return s;
  });
}

}  // namespace thx::tex::gen
