#pragma once
// Small triangle meshes for the BVH and mesh god-object tests: height-field grids built from a
// function, and the height of such a grid under a point (to check a proxy never goes below it).
#include <cmath>
#include <cstdint>
#include <functional>

#include "server/triangle_mesh.hpp"

namespace thx::test {

// n x n quads over [-half, half]^2, z = height(x, y) at the vertices, split as reliefGridMesh.
inline srv::TriangleMesh gridMesh(int n, double half, const std::function<double(double, double)>& height) {
  srv::TriangleMesh m;
  const auto side = std::uint32_t(n + 1);
  for (int r = 0; r <= n; ++r) {
    for (int c = 0; c <= n; ++c) {
      const double x = -half + 2 * half * c / n, y = -half + 2 * half * r / n;
      m.vertices.emplace_back(x, y, height(x, y));
    }
  }
  const auto id = [side](int r, int c) { return std::uint32_t(r) * side + std::uint32_t(c); };
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      m.triangles.push_back({id(r, c), id(r, c + 1), id(r + 1, c + 1)});
      m.triangles.push_back({id(r, c), id(r + 1, c + 1), id(r + 1, c)});
    }
  }
  return m;
}

// Height of gridMesh(n, half, ...) at (x, y) inside the grid: the plane of the triangle below.
inline double gridHeight(const srv::TriangleMesh& m, int n, double half, double x, double y) {
  const double cell = 2 * half / n;
  const double fx = (x + half) / cell, fy = (y + half) / cell;
  const int c = std::min(n - 1, std::max(0, int(std::floor(fx)))), r = std::min(n - 1, std::max(0, int(std::floor(fy))));
  const double s = fx - c, t = fy - r;  // in the quad; the diagonal runs (0,0)-(1,1)
  const auto z = [&](int rr, int cc) { return m.vertices[std::size_t(rr * (n + 1) + cc)].z(); };
  if (s >= t) return z(r, c) + s * (z(r, c + 1) - z(r, c)) + t * (z(r + 1, c + 1) - z(r, c + 1));
  return z(r, c) + t * (z(r + 1, c) - z(r, c)) + s * (z(r + 1, c + 1) - z(r + 1, c));
}

}  // namespace thx::test
