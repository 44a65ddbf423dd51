#include "server/triangle_mesh.hpp"

#include <string>

#include "base/error.hpp"

namespace thx::srv {

TriangleMesh reliefGridMesh(const tex::TexturedSurface& surface, int n) {
  if (n < 1 || n > 4096)
    throw thx::Error(thx::Error::Kind::Config, "reliefGridMesh: n = " + std::to_string(n) + ", expected 1..4096");
  TriangleMesh m;
  const Eigen::Vector2d size = surface.mapping().size_m;
  const std::size_t side = std::size_t(n) + 1;
  m.vertices.reserve(side * side);
  for (int r = 0; r <= n; ++r) {
    const double y = (double(r) / n - 0.5) * size.y();
    for (int c = 0; c <= n; ++c) {
      const double x = (double(c) / n - 0.5) * size.x();
      m.vertices.emplace_back(x, y, surface.at(x, y).height_m);
    }
  }
  m.triangles.reserve(2 * std::size_t(n) * std::size_t(n));
  const auto id = [side](int r, int c) { return std::uint32_t(std::size_t(r) * side + std::size_t(c)); };
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      m.triangles.push_back({id(r, c), id(r, c + 1), id(r + 1, c + 1)});
      m.triangles.push_back({id(r, c), id(r + 1, c + 1), id(r + 1, c)});
    }
  }
  return m;
}

}  // namespace thx::srv
