// The triangle across each edge (meshes/textured_mesh.hpp, triangleNeighbours): matched by the
// positions of the edge's ends, so a seam's split vertices join; none on a border, across an
// edge of three triangles, or across an edge two triangles run the same way.
#include <gtest/gtest.h>

#include "meshes/mesh_generators.hpp"
#include "meshes/textured_mesh.hpp"

namespace test_triangle_neighbours {

using namespace thx::mesh;

// The corners (k + 1, k + 2) of triangle t: the edge [t][k] names.
std::pair<std::uint32_t, std::uint32_t> edgeOf(const TexturedMesh& m, std::uint32_t t, std::size_t k) {
  return {m.triangles[t][(k + 1) % 3], m.triangles[t][(k + 2) % 3]};
}

// Every neighbour names the other back across an edge with the same two positions, run the
// other way; returns the number of edges without one.
std::size_t expectConsistent(const TexturedMesh& m, const std::vector<Triangle>& n) {
  std::size_t borders = 0;
  for (std::uint32_t t = 0; t < n.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t u = n[t][k];
      if (u == kNoNeighbour) {
        ++borders;
        continue;
      }
      const auto [from, to] = edgeOf(m, t, k);
      std::size_t back = 3;
      for (std::size_t q = 0; q < 3; ++q)
        if (n[u][q] == t) back = q;
      EXPECT_LT(back, 3u) << "triangle " << u << " does not name " << t << " back";
      if (back == 3) continue;
      const auto [from_u, to_u] = edgeOf(m, u, back);
      EXPECT_EQ(m.positions[from], m.positions[to_u]);
      EXPECT_EQ(m.positions[to], m.positions[from_u]);
    }
  return borders;
}

TEST(TriangleNeighbours, AClosedSphereHasNoBorderAndItsSeamJoins) {
  // With frames built the sphere's vertices are split along its u seam (two uvs per position).
  TexturedMesh m = sphere(0.03, 48, 24, 0.01).mesh;
  buildVertexFrames(m);
  EXPECT_EQ(expectConsistent(m, triangleNeighbours(m)), 0u);
}

TEST(TriangleNeighbours, AnOpenCylinderHasItsRimsAsBorders) {
  const TexturedMesh m = cylinder(0.03, 0.05, 48, 10, 0.01).mesh;
  // Two rims of 48 edges each.
  EXPECT_EQ(expectConsistent(m, triangleNeighbours(m)), 96u);
}

TEST(TriangleNeighbours, AnEdgeOfThreeTrianglesOrRunTwiceOneWayJoinsNone) {
  TexturedMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {1, 1, 1}, {0.5, 0.5, 2}};
  m.uvs.assign(m.positions.size(), Eigen::Vector2d::Zero());
  // Edge 0-1 is shared by three triangles: no neighbour across it for any of them.
  m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  std::vector<Triangle> n = triangleNeighbours(m);
  for (std::uint32_t t = 0; t < 3; ++t) EXPECT_EQ(n[t][2], kNoNeighbour) << t;
  // Two triangles running edge 5-6 the same way (inconsistent winding): none; the third runs
  // it the other way, but the edge is taken.
  m.triangles = {{5, 6, 0}, {5, 6, 1}, {6, 5, 2}};
  n = triangleNeighbours(m);
  for (std::uint32_t t = 0; t < 3; ++t) EXPECT_EQ(n[t][2], kNoNeighbour) << t;
  // Two triangles run it opposite ways: neighbours across it.
  m.triangles = {{5, 6, 0}, {6, 5, 2}};
  n = triangleNeighbours(m);
  EXPECT_EQ(n[0][2], 1u);
  EXPECT_EQ(n[1][2], 0u);
}

TEST(TriangleNeighbours, SplitVerticesAtOnePositionAreOnePoint) {
  // Two triangles sharing an edge through four vertices, the shared positions duplicated (as a
  // texture seam splits them), one of them at -0.0.
  TexturedMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-0.0, 0, 0}, {1, 0, 0}, {0, -1, 0}};
  m.uvs.assign(m.positions.size(), Eigen::Vector2d::Zero());
  m.triangles = {{0, 1, 2}, {4, 3, 5}};
  const std::vector<Triangle> n = triangleNeighbours(m);
  EXPECT_EQ(n[0][2], 1u);
  EXPECT_EQ(n[1][2], 0u);
  EXPECT_EQ(expectConsistent(m, n), 4u);
}

}  // namespace test_triangle_neighbours
