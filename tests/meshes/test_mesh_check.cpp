// checkMesh (meshes/mesh_check.hpp): each refusal on a small hand-built mesh, with the message
// naming the mesh and the element; seams (the same position under two vertex indices) keep a
// surface closed; nothing but thx::Error escapes.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "base/error.hpp"
#include "meshes/mesh_check.hpp"

namespace test_mesh_check {

using namespace thx;
using namespace thx::mesh;

namespace {

// A regular tetrahedron, faces counter-clockwise seen from outside.
TexturedMesh tetrahedron() {
  TexturedMesh m;
  m.source = "tetra";
  m.positions = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  m.uvs = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  m.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  return m;
}

// An octahedron textured like a UV sphere: u = longitude / 2 pi, v = latitude. The equator's
// vertex at longitude 0 is there twice, at u = 0 and u = 1 (the seam): same position, two indices.
TexturedMesh seamedOctahedron() {
  TexturedMesh m;
  m.source = "octahedron";
  m.positions = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0, 1}, {0, 0, -1}};
  m.uvs = {{0, 0.5}, {0.25, 0.5}, {0.5, 0.5}, {0.75, 0.5}, {1, 0.5}, {0.5, 1}, {0.5, 0}};
  for (std::uint32_t k = 0; k < 4; ++k) {
    m.triangles.push_back({k, k + 1, 5});
    m.triangles.push_back({k + 1, k, 6});
  }
  return m;
}

// What checkMesh says: "accepted" or the message of a Config error (anything else fails).
std::string verdict(const TexturedMesh& m, const MeshLimits& limits = {}) {
  try {
    checkMesh(m, limits);
    return "accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::Config) << e.what();
    return e.what();
  }
}

MeshLimits closed() {
  MeshLimits l;
  l.require_closed = true;
  return l;
}

}  // namespace

TEST(MeshCheck, ClosedMeshesPass) {
  EXPECT_EQ(verdict(tetrahedron(), closed()), "accepted");
  EXPECT_EQ(verdict(seamedOctahedron(), closed()), "accepted");
}

TEST(MeshCheck, SeamVerticesCountAsOnePositionWhateverTheSignOfZero) {
  TexturedMesh m = seamedOctahedron();
  m.positions[4] = {1.0, -0.0, -0.0};  // equal to (1, 0, 0), other bits
  EXPECT_EQ(verdict(m, closed()), "accepted");
  m.positions[4].x() = std::nextafter(1.0, 2.0);  // one ulp apart: a crack, not a seam
  EXPECT_EQ(verdict(m, closed()), "mesh octahedron: edge 5->0 of triangle 0 (0, 1, 5) belongs to no other triangle (a "
                                  "hole); expected every edge shared by exactly two triangles (a closed surface)");
}

TEST(MeshCheck, NoTriangles) {
  TexturedMesh m = tetrahedron();
  m.triangles.clear();
  EXPECT_EQ(verdict(m), "mesh tetra: no triangles; expected at least one");
}

TEST(MeshCheck, MoreTrianglesThanTheLimit) {
  MeshLimits l;
  l.max_triangles = 3;
  EXPECT_EQ(verdict(tetrahedron(), l), "mesh tetra: 4 triangles, more than the limit of 3 (MeshLimits::max_triangles)");
}

TEST(MeshCheck, NoTextureCoordinates) {
  TexturedMesh m = tetrahedron();
  m.uvs.clear();
  EXPECT_EQ(verdict(m), "mesh tetra: 0 texture coordinates for 4 vertices; expected one per vertex (a mesh without "
                        "texture coordinates needs a projection)");
}

TEST(MeshCheck, NonFiniteValues) {
  TexturedMesh m = tetrahedron();
  m.positions[2].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(verdict(m), "mesh tetra: vertex 2 has a non-finite position (-1, nan, -1); expected finite coordinates");
  m = tetrahedron();
  m.uvs[3].x() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(verdict(m), "mesh tetra: vertex 3 has a non-finite texture coordinate (inf, 1); expected finite coordinates");
}

TEST(MeshCheck, VertexIndexOutOfRange) {
  TexturedMesh m = tetrahedron();
  m.triangles[2] = {0, 2, 9};
  EXPECT_EQ(verdict(m), "mesh tetra: triangle 2 (0, 2, 9) uses vertex 9, but the mesh has 4 vertices; expected indices "
                        "below 4");
}

TEST(MeshCheck, TriangleRepeatingAVertex) {
  TexturedMesh m = tetrahedron();
  m.triangles[1] = {0, 3, 3};
  EXPECT_EQ(verdict(m), "mesh tetra: triangle 1 (0, 3, 3) repeats vertex 3; expected three different vertices");
}

TEST(MeshCheck, ZeroAreaTriangle) {
  TexturedMesh m = tetrahedron();
  m.positions.push_back({0, 0, -1});  // the midpoint of vertices 1 and 2
  m.uvs.push_back({0.5, 0.5});
  m.triangles.push_back({1, 4, 2});
  EXPECT_EQ(verdict(m), "mesh tetra: triangle 4 (1, 4, 2) has area 0 m^2; expected more than 1e-12 x the bounding-box "
                        "diagonal squared (1.2e-11 m^2)");
  // A sliver well above the bound passes (its edges make a fin, refused only when the mesh must
  // be closed).
  m.positions[4] = {0, 0, -1 + 1e-5};
  EXPECT_EQ(verdict(m), "accepted");
}

TEST(MeshCheck, InconsistentWinding) {
  TexturedMesh m = tetrahedron();
  m.triangles[3] = {1, 2, 3};  // wound clockwise seen from outside
  EXPECT_EQ(verdict(m), "mesh tetra: triangles 0 and 3 both run edge 1->2: inconsistent winding; expected neighbouring "
                        "triangles to run a shared edge in opposite directions (counter-clockwise seen from outside)");
}

TEST(MeshCheck, InconsistentWindingAcrossASeam) {
  TexturedMesh m = seamedOctahedron();
  std::swap(m.triangles[6][0], m.triangles[6][1]);  // (4, 3, 5): the seam's copy of vertex 0
  EXPECT_EQ(verdict(m), "mesh octahedron: triangles 0 and 6 both run edge 5->0: inconsistent winding; expected "
                        "neighbouring triangles to run a shared edge in opposite directions (counter-clockwise seen "
                        "from outside)");
}

TEST(MeshCheck, OpenSurfaceOnlyWhenClosedIsRequired) {
  TexturedMesh m = tetrahedron();
  m.triangles.pop_back();
  EXPECT_EQ(verdict(m), "accepted");
  EXPECT_EQ(verdict(m, closed()), "mesh tetra: edge 1->2 of triangle 0 (0, 1, 2) belongs to no other triangle (a hole); "
                                  "expected every edge shared by exactly two triangles (a closed surface)");
}

TEST(MeshCheck, NonManifoldEdgeOnlyWhenClosedIsRequired) {
  // A fin: a third triangle on the tetrahedron's edge 0-1.
  TexturedMesh m = tetrahedron();
  m.positions.push_back({3, 0, 0});
  m.uvs.push_back({2, 0});
  m.triangles.push_back({0, 1, 4});
  EXPECT_EQ(verdict(m), "accepted");  // its winding is not compared either
  EXPECT_EQ(verdict(m, closed()), "mesh tetra: edge 0->1 of triangle 0 is shared by 3 triangles (0, 1, 4); expected "
                                  "every edge shared by exactly two triangles (a closed surface)");
}

TEST(MeshCheck, OnlyThxErrorsEscapeForAnyMesh) {
  // Random small meshes: indices past the end, repeated corners, and now and then a NaN, an
  // infinity, a huge or tiny coordinate or a negative zero among small whole numbers.
  std::uint64_t s = 0x9e3779b97f4a7c15ull;
  const auto next = [&] {
    s ^= s << 13, s ^= s >> 7, s ^= s << 17;
    return s;
  };
  const double odd[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 1e300,
                        1e-300, -0.0};
  const auto value = [&] {
    const std::uint64_t k = next() % 64;
    return k < 59 ? double(k % 3) - 1.0 : odd[k - 59];
  };
  int accepted = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    TexturedMesh m;
    m.source = "random";
    const std::size_t nv = next() % 6, nt = next() % 6;
    for (std::size_t v = 0; v < nv; ++v) {
      m.positions.push_back({value(), value(), value()});
      m.uvs.push_back({value(), value()});
    }
    if (next() % 8 == 0 && !m.uvs.empty()) m.uvs.pop_back();
    for (std::size_t t = 0; t < nt; ++t)
      m.triangles.push_back({std::uint32_t(next() % 7), std::uint32_t(next() % 7), std::uint32_t(next() % 7)});
    MeshLimits l;
    l.require_closed = next() % 2 == 0;
    try {
      checkMesh(m, l);
      ++accepted;
    } catch (const Error& e) {
      ASSERT_EQ(e.kind(), Error::Kind::Config);
      ASSERT_EQ(std::string(e.what()).rfind("mesh random: ", 0), 0u) << e.what();
    }
  }
  EXPECT_GT(accepted, 0);
}

}  // namespace test_mesh_check
