#include "clients/visual/mesh_builders.hpp"

#include <cmath>
#include <numbers>

namespace thx::visual {
namespace {

// Quads (a, b, c, d counter-clockwise) as two triangles.
void addQuad(MeshData& m, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
}

std::uint32_t addVertex(MeshData& m, const Eigen::Vector3f& p, const Eigen::Vector3f& n) {
  m.positions.push_back(p);
  m.normals.push_back(n);
  return std::uint32_t(m.positions.size() - 1);
}

}  // namespace

MeshData planeQuad(const Eigen::Vector2d& size_m) {
  MeshData m;
  const float hx = float(size_m.x() / 2), hy = float(size_m.y() / 2);
  const Eigen::Vector3f up(0, 0, 1);
  addVertex(m, {-hx, -hy, 0}, up);
  addVertex(m, {hx, -hy, 0}, up);
  addVertex(m, {hx, hy, 0}, up);
  addVertex(m, {-hx, hy, 0}, up);
  addQuad(m, 0, 1, 2, 3);
  return m;
}

MeshData displacedGrid(const tex::TexturedSurface& surface, int n) {
  MeshData m;
  const Eigen::Vector2d size = surface.mapping().size_m;
  for (int r = 0; r <= n; ++r) {
    for (int c = 0; c <= n; ++c) {
      const double x = (double(c) / n - 0.5) * size.x(), y = (double(r) / n - 0.5) * size.y();
      const tex::SurfacePoint p = surface.at(x, y);
      addVertex(m, Eigen::Vector3f(float(x), float(y), float(p.height_m)), p.n_local.cast<float>());
    }
  }
  const auto at = [n](int r, int c) { return std::uint32_t(r * (n + 1) + c); };
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) addQuad(m, at(r, c), at(r, c + 1), at(r + 1, c + 1), at(r + 1, c));
  return m;
}

MeshData unitSphere(int slices, int stacks) {
  MeshData m;
  for (int s = 0; s <= stacks; ++s) {
    const double theta = std::numbers::pi * s / stacks;  // from the north pole
    for (int k = 0; k <= slices; ++k) {
      const double phi = 2 * std::numbers::pi * k / slices;
      const Eigen::Vector3f p(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                              float(std::cos(theta)));
      addVertex(m, p, p);
    }
  }
  for (int s = 0; s < stacks; ++s)
    for (int k = 0; k < slices; ++k) {
      const auto a = std::uint32_t(s * (slices + 1) + k), b = a + std::uint32_t(slices + 1);
      addQuad(m, a, b, b + 1, a + 1);
    }
  return m;
}

MeshData unitBox() {
  MeshData m;
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign : {-1, 1}) {
      Eigen::Vector3f n = Eigen::Vector3f::Zero();
      n[axis] = float(sign);
      Eigen::Vector3f u = Eigen::Vector3f::Zero(), v = Eigen::Vector3f::Zero();
      u[(axis + 1) % 3] = 0.5f;
      v[(axis + 2) % 3] = 0.5f;
      if (sign < 0) std::swap(u, v);  // keeps the winding counter-clockwise from outside
      const Eigen::Vector3f c = n * 0.5f;
      const std::uint32_t a = addVertex(m, c - u - v, n);
      addVertex(m, c + u - v, n);
      addVertex(m, c + u + v, n);
      addVertex(m, c - u + v, n);
      addQuad(m, a, a + 1, a + 2, a + 3);
    }
  }
  return m;
}

MeshData unitCylinder(int slices) {
  MeshData m;
  for (int k = 0; k <= slices; ++k) {
    const double phi = 2 * std::numbers::pi * k / slices;
    const Eigen::Vector3f n(float(std::cos(phi)), float(std::sin(phi)), 0.0f);
    addVertex(m, n + Eigen::Vector3f(0, 0, -0.5f), n);
    addVertex(m, n + Eigen::Vector3f(0, 0, 0.5f), n);
  }
  for (int k = 0; k < slices; ++k) {
    const auto a = std::uint32_t(2 * k);
    addQuad(m, a, a + 2, a + 3, a + 1);
  }
  for (float z : {-0.5f, 0.5f}) {
    const Eigen::Vector3f n(0, 0, z > 0 ? 1.0f : -1.0f);
    const std::uint32_t centre = addVertex(m, {0, 0, z}, n);
    for (int k = 0; k <= slices; ++k) {
      const double phi = 2 * std::numbers::pi * k / slices;
      addVertex(m, {float(std::cos(phi)), float(std::sin(phi)), z}, n);
    }
    for (int k = 0; k < slices; ++k) {
      const std::uint32_t a = centre + 1 + std::uint32_t(k);
      if (z > 0) m.indices.insert(m.indices.end(), {centre, a, a + 1});
      else m.indices.insert(m.indices.end(), {centre, a + 1, a});
    }
  }
  return m;
}

}  // namespace thx::visual
