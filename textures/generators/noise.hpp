#pragma once
// Internal to the generators: seeded smooth noise and cell networks with exact gradients, shared
// by porcelain, stone, ceramic_tile and metal. Everything is keyed by (seed, lattice index, salt)
// through random01, and every lattice wraps with the tile, so a pattern whose cell divides the
// extent tiles seamlessly.
#include "textures/generators/common.hpp"

namespace thx::tex::gen {

// Perlin gradient noise on a square lattice of cell `cell` (metres) that repeats every n cells:
// unit gradients keyed per lattice point, quintic fade. Value roughly in [-0.7, 0.7], C2-smooth.
inline SurfacePoint gradientNoise(double x, double y, double cell, std::int64_t n, std::uint64_t seed,
                                  std::uint64_t salt) {
  const double gx = x / cell, gy = y / cell;
  const double fxl = std::floor(gx), fyl = std::floor(gy);
  const auto ix = std::int64_t(fxl), iy = std::int64_t(fyl);
  const double fx = gx - fxl, fy = gy - fyl;
  auto grad = [&](std::int64_t di, std::int64_t dj) {
    const double a = 2.0 * kPi * random01(seed, wrapIndex(ix + di, n), wrapIndex(iy + dj, n), salt);
    return Eigen::Vector2d(std::cos(a), std::sin(a));
  };
  const Eigen::Vector2d g00 = grad(0, 0), g10 = grad(1, 0), g01 = grad(0, 1), g11 = grad(1, 1);
  const double a = g00.x() * fx + g00.y() * fy, b = g10.x() * (fx - 1) + g10.y() * fy;
  const double c = g01.x() * fx + g01.y() * (fy - 1), d = g11.x() * (fx - 1) + g11.y() * (fy - 1);
  auto fade = [](double t) { return t * t * t * (t * (t * 6 - 15) + 10); };
  auto dfade = [](double t) { return 30 * t * t * (t * (t - 2) + 1); };
  const double u = fade(fx), v = fade(fy), du = dfade(fx), dv = dfade(fy);
  const double k = a - b - c + d;
  const Eigen::Vector2d gk = g00 - g10 - g01 + g11;
  const Eigen::Vector2d grad_in_cells = g00 + u * (g10 - g00) + v * (g01 - g00) + u * v * gk +
                                        Eigen::Vector2d(du * ((b - a) + v * k), dv * ((c - a) + u * k));
  return {a + u * (b - a) + v * (c - a) + u * v * k, grad_in_cells.x() / cell, grad_in_cells.y() / cell};
}

// Fractal sum of gradient noise: octave o has wavelength base / 2^o (rounded so it divides the
// extent) and amplitude amplitude * gain^o. Octaves shorter than three texels (min_wavelength)
// are left out: on the grid they would only alias.
inline SurfacePoint fractalNoise(double x, double y, double extent, double base, int octaves, double amplitude,
                                 double gain, double min_wavelength, std::uint64_t seed, std::uint64_t salt) {
  SurfacePoint s;
  double wavelength = base, amp = amplitude;
  for (int o = 0; o < octaves; ++o, wavelength /= 2.0, amp *= gain) {
    const std::int64_t n = periodsIn(extent, wavelength);
    const double cell = extent / double(n);
    if (cell < min_wavelength) break;
    const SurfacePoint q = gradientNoise(x, y, cell, n, seed, salt + std::uint64_t(o));
    s.h += amp * q.h;
    s.dhdx += amp * q.dhdx;
    s.dhdy += amp * q.dhdy;
  }
  return s;
}

// Distance from a point to the border of its cell in a jittered-grid Voronoi network (one seeded
// site per cell of side `cell`, n cells per period, sites within the middle `jitter` of their
// cell) and the gradient of that distance. The distance to the border with a neighbour's cell is
// the distance to the bisector of the two sites, linear in the point, so its gradient is the unit
// vector between the sites; the nearest border wins (a crease where two borders are equally near).
struct CellBorder {
  double s = 0.0;              // metres to the nearest border
  Eigen::Vector2d grad{0, 0};  // ds/d(x, y)
  std::int64_t ci = 0, cj = 0; // the cell whose site is nearest
};

inline Eigen::Vector2d voronoiSite(std::int64_t ci, std::int64_t cj, double cell, std::int64_t n, double jitter,
                                   std::uint64_t seed, std::uint64_t salt) {
  const double ox = 0.5 + jitter * (random01(seed, wrapIndex(ci, n), wrapIndex(cj, n), salt) - 0.5);
  const double oy = 0.5 + jitter * (random01(seed, wrapIndex(ci, n), wrapIndex(cj, n), salt + 1) - 0.5);
  return {(double(ci) + ox) * cell, (double(cj) + oy) * cell};
}

inline CellBorder cellBorder(double x, double y, double cell, std::int64_t n, double jitter, std::uint64_t seed,
                             std::uint64_t salt) {
  const Eigen::Vector2d p(x, y);
  const auto i0 = std::int64_t(std::floor(x / cell)), j0 = std::int64_t(std::floor(y / cell));
  CellBorder out;
  Eigen::Vector2d near{0, 0};
  double best = std::numeric_limits<double>::infinity();
  // 5 x 5 cells: with sites anywhere in the middle 90 % of a cell, the nearest can be two cells away.
  for (std::int64_t dj = -2; dj <= 2; ++dj)
    for (std::int64_t di = -2; di <= 2; ++di) {
      const Eigen::Vector2d c = voronoiSite(i0 + di, j0 + dj, cell, n, jitter, seed, salt);
      const double dist2 = (p - c).squaredNorm();
      if (dist2 < best) {
        best = dist2;
        near = c;
        out.ci = i0 + di;
        out.cj = j0 + dj;
      }
    }
  out.s = std::numeric_limits<double>::infinity();
  for (std::int64_t dj = -2; dj <= 2; ++dj)
    for (std::int64_t di = -2; di <= 2; ++di) {
      if (di == out.ci - i0 && dj == out.cj - j0) continue;
      const Eigen::Vector2d c = voronoiSite(out.ci + di, out.cj + dj, cell, n, jitter, seed, salt);
      const Eigen::Vector2d along = c - near;
      const double len = along.norm();
      const double s = (c.squaredNorm() - near.squaredNorm() - 2.0 * p.dot(along)) / (2.0 * len);
      if (s < out.s) {
        out.s = s;
        out.grad = -along / len;
      }
    }
  return out;
}

// A groove of half-width w and depth `depth` along a line at distance s (gradient ds) from the
// point: raised-cosine profile, flat on the line and where it meets the surface around it.
inline SurfacePoint grooveAt(double s, const Eigen::Vector2d& ds, double w, double depth) {
  if (s >= w || depth <= 0.0) return {};
  const double c = 0.5 * (1.0 + std::cos(kPi * s / w));
  const double dc = -0.5 * kPi / w * std::sin(kPi * s / w);
  return {-depth * c, -depth * dc * ds.x(), -depth * dc * ds.y()};
}

inline SurfacePoint operator+(SurfacePoint a, const SurfacePoint& b) {
  return {a.h + b.h, a.dhdx + b.dhdx, a.dhdy + b.dhdy};
}

// Fractal noise cut by raised-cosine cracks along the borders of a Voronoi network: the relief of
// porcelain (faint undulation, crazing) and of stone (roughness, cleft planes) alike.
struct CrackedNoise {
  double extent = 0.0;
  double wavelength = 0.0, amplitude = 0.0, gain = 0.5;  // fractalNoise's first octave and ratio
  int octaves = 1;
  double min_wavelength = 0.0;                  // three texels
  double crack_cell_request = 0.0;              // grown or shrunk to divide the extent
  double jitter = 0.8;                          // of the Voronoi sites
  double crack_width = 0.0, crack_depth = 0.0;  // depth 0: no cracks
  std::uint64_t seed = 0, salt = 0;
};

inline TextureMap rasterizeCrackedNoise(int size, const CrackedNoise& c) {
  const std::int64_t n = periodsIn(c.extent, c.crack_cell_request);
  const double cell = c.extent / double(n);
  return rasterize(size, c.extent, [&c, n, cell](double x, double y) {
    SurfacePoint s = fractalNoise(x, y, c.extent, c.wavelength, c.octaves, c.amplitude, c.gain, c.min_wavelength,
                                  c.seed, c.salt);
    if (c.crack_depth > 0.0) {
      const CellBorder b = cellBorder(x, y, cell, n, c.jitter, c.seed, c.salt + 16);
      s = s + grooveAt(b.s, b.grad, c.crack_width / 2.0, c.crack_depth);
    }
    return s;
  });
}

}  // namespace thx::tex::gen
