// The mesh god object's BVH: its answers equal brute force over every triangle, on random
// segments and on segments through vertices and edges; the relief grid it is built over.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

#include "base/error.hpp"
#include "meshes/mesh_generators.hpp"
#include "meshes/textured_mesh.hpp"
#include "server/triangle_bvh.hpp"
#include "server/triangle_mesh.hpp"
#include "tests/server/mesh_fixtures.hpp"
#include "textures/generators.hpp"

namespace test_triangle_bvh {

using namespace thx;
using srv::TriangleBvh;

namespace {

// The reference: the primitive test on every triangle, lowest t, ties to the lower index.
TriangleBvh::Hit bruteForce(const TriangleBvh& bvh, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  TriangleBvh::Hit best;
  double best_t = std::numeric_limits<double>::infinity();
  for (std::uint32_t i = 0; i < bvh.triangles().size(); ++i) {
    double t = 0;
    if (bvh.entersTriangle(i, a, b, t) && t < best_t) {
      best_t = t;
      best.hit = true;
      best.t = t;
      best.triangle = i;
    }
  }
  return best;
}

void expectSame(const TriangleBvh& bvh, const Eigen::Vector3d& a, const Eigen::Vector3d& b, int& hits) {
  const TriangleBvh::Hit h = bvh.firstEntry(a, b), r = bruteForce(bvh, a, b);
  ASSERT_EQ(h.hit, r.hit) << "a " << a.transpose() << " b " << b.transpose();
  if (!r.hit) return;
  ++hits;
  EXPECT_EQ(h.t, r.t);
  EXPECT_EQ(h.triangle, r.triangle);
  EXPECT_LT((h.point - (a + r.t * (b - a))).norm(), 1e-15);
}

double bumpy(double x, double y) {
  return 0.002 * std::sin(900 * x) * std::cos(700 * y) + 0.001 * std::sin(3000 * x * y);
}

}  // namespace

TEST(TriangleBvh, EqualsBruteForceOnRandomSegments) {
  const srv::TriangleMesh mesh = test::gridMesh(12, 0.01, bumpy);
  const TriangleBvh bvh(mesh);
  EXPECT_LE(bvh.depth(), 7);  // median split: log2(288 / 4) rounded up
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> xy(-0.012, 0.012), z(-0.005, 0.005);
  int hits = 0;
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d a(xy(rng), xy(rng), z(rng)), b(xy(rng), xy(rng), z(rng));
    expectSame(bvh, a, b, hits);
    // Short segments too: a servo tick's motion is a fraction of a triangle.
    expectSame(bvh, a, a + 0.02 * (b - a), hits);
  }
  EXPECT_GT(hits, 300);  // the sample exercises hits, not only misses
}

// A textured mesh's hierarchy is built over the mesh's own positions and triangles (no copy: the
// sweeps and the renderer read the same corners), and answers as one over a copy of them does.
// A temporary's arrays would dangle, so building from one does not compile.
static_assert(!std::is_constructible_v<TriangleBvh, srv::TriangleMesh&&>);
static_assert(!std::is_constructible_v<TriangleBvh, std::vector<Eigen::Vector3d>&&,
                                       const std::vector<std::array<std::uint32_t, 3>>&>);
static_assert(!std::is_constructible_v<TriangleBvh, const std::vector<Eigen::Vector3d>&,
                                       std::vector<std::array<std::uint32_t, 3>>&&>);
TEST(TriangleBvh, BuiltOverATexturedMeshItReadsTheMeshsOwnArrays) {
  const mesh::TexturedMesh sphere = mesh::sphere(0.03, 24, 12, 0.01).mesh;
  const TriangleBvh bvh(sphere.positions, sphere.triangles);
  EXPECT_EQ(&bvh.vertices(), &sphere.positions);
  EXPECT_EQ(&bvh.triangles(), &sphere.triangles);
  srv::TriangleMesh copy;
  copy.vertices = sphere.positions;
  copy.triangles = sphere.triangles;
  const TriangleBvh over_copy(copy);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> c(-0.035, 0.035);
  int hits = 0;
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d a(c(rng), c(rng), c(rng)), b(c(rng), c(rng), c(rng));
    const TriangleBvh::Hit x = bvh.firstEntry(a, b), y = over_copy.firstEntry(a, b);
    ASSERT_EQ(x.hit, y.hit) << i;
    if (!x.hit) continue;
    ++hits;
    EXPECT_EQ(x.triangle, y.triangle) << i;
    EXPECT_EQ(x.t, y.t) << i;
  }
  EXPECT_GT(hits, 100);  // segments through a 3 cm sphere from a 7 cm box: many enter it
}

TEST(TriangleBvh, NearestEqualsBruteForce) {
  // The nearest triangle within a distance (the textured mesh renderer's question where the pen
  // stands over the flat faces): the same triangle and distance as every triangle tried in turn
  // with the same closest-point function (mesh::closestBarycentric, tested against a sampled
  // search in tests/meshes/), and nothing beyond the bound. Ties go to the lower index.
  const srv::TriangleMesh mesh = test::gridMesh(12, 0.01, bumpy);
  const TriangleBvh bvh(mesh);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> xy(-0.012, 0.012), z(-0.006, 0.006);
  int found = 0, beyond = 0;
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d p(xy(rng), xy(rng), z(rng));
    double best = std::numeric_limits<double>::infinity();
    std::uint32_t best_t = 0;
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& tri = mesh.triangles[t];
      const auto& v = mesh.vertices;
      const Eigen::Vector3d b = mesh::closestBarycentric(v[tri[0]], v[tri[1]], v[tri[2]], p);
      const double d2 = (b.x() * v[tri[0]] + b.y() * v[tri[1]] + b.z() * v[tri[2]] - p).squaredNorm();
      if (d2 < best) best = d2, best_t = t;
    }
    best = std::sqrt(best);
    const double bound = i % 2 ? 0.003 : 1.0;
    const TriangleBvh::Nearest n = bvh.nearest(p, bound);
    if (best > bound) {
      EXPECT_FALSE(n.found);
      ++beyond;
      continue;
    }
    ASSERT_TRUE(n.found);
    ++found;
    EXPECT_EQ(n.triangle, best_t);
    EXPECT_NEAR(n.distance, best, 1e-15);
  }
  EXPECT_GT(found, 400);
  EXPECT_GT(beyond, 10);  // the bound is exercised too
}

TEST(TriangleBvh, VerticalSegmentsThroughVerticesAndEdgesHitExactlyOnce) {
  // Straight down through every vertex and edge midpoint of the grid: ties between the
  // triangles sharing them resolve to the lowest index, as in brute force, and none is missed.
  const int n = 8;
  const double half = 0.004;
  const srv::TriangleMesh mesh = test::gridMesh(n, half, bumpy);
  const TriangleBvh bvh(mesh, 2);
  int hits = 0;
  for (int r = 0; r <= 2 * n; ++r) {
    for (int c = 0; c <= 2 * n; ++c) {
      const double x = -half + half * c / n, y = -half + half * r / n;
      expectSame(bvh, {x, y, 0.01}, {x, y, -0.01}, hits);
      EXPECT_TRUE(bvh.firstEntry({x, y, 0.01}, {x, y, -0.01}).hit) << x << " " << y;
    }
  }
  EXPECT_EQ(hits, (2 * n + 1) * (2 * n + 1));
}

TEST(TriangleBvh, OnlyFrontEntriesAndSkippedTriangles) {
  const srv::TriangleMesh mesh = test::gridMesh(4, 0.01, [](double, double) { return -0.001; });
  const TriangleBvh bvh(mesh);
  // From below (a back face) and parallel above: no entry.
  EXPECT_FALSE(bvh.firstEntry({0.001, 0.002, -0.003}, {0.001, 0.002, 0.003}).hit);
  EXPECT_FALSE(bvh.firstEntry({-0.009, 0.002, 0.0}, {0.009, 0.002, 0.0}).hit);
  const TriangleBvh::Hit h = bvh.firstEntry({0.001, 0.002, 0.003}, {0.001, 0.002, -0.003});
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.t, 4.0 / 6.0, 1e-15);
  EXPECT_NEAR(h.point.z(), -0.001, 1e-15);
  EXPECT_NEAR(bvh.plane(h.triangle).n.z(), 1.0, 1e-15);
  // Skipping the face hit leaves nothing below it (flat: no other face under that point).
  EXPECT_FALSE(bvh.firstEntry({0.001, 0.002, 0.003}, {0.001, 0.002, -0.003}, &h.triangle, 1).hit);
}

TEST(TriangleBvh, RejectsBadMeshes) {
  srv::TriangleMesh empty;
  EXPECT_THROW(TriangleBvh{empty}, thx::Error);
  srv::TriangleMesh bad = test::gridMesh(1, 0.01, [](double, double) { return 0.0; });
  bad.triangles[0][2] = 99;
  EXPECT_THROW(TriangleBvh{bad}, thx::Error);
  srv::TriangleMesh flat = test::gridMesh(1, 0.01, [](double, double) { return 0.0; });
  flat.triangles[0] = {0, 1, 1};
  EXPECT_THROW(TriangleBvh{flat}, thx::Error);
}

TEST(ReliefGridMesh, VerticesOnTheSampledReliefFacesUp) {
  tex::GenerateRequest r;
  r.kind = "sine";
  r.size = 32;
  r.params = {{"amplitude", 0.5e-3}, {"period", 0.01}, {"extent", 0.02}};
  const tex::TextureMap map = tex::generate(r);
  tex::PlaneMapping mapping;
  mapping.size_m = {0.02, 0.02};
  const tex::TexturedSurface surface(map, mapping, tex::SampleOptions{}, true);
  const int n = 16;
  const srv::TriangleMesh mesh = srv::reliefGridMesh(surface, n);
  ASSERT_EQ(mesh.vertices.size(), std::size_t((n + 1) * (n + 1)));
  ASSERT_EQ(mesh.triangles.size(), std::size_t(2 * n * n));
  double lowest = 0;
  for (const Eigen::Vector3d& v : mesh.vertices) {
    EXPECT_EQ(v.z(), surface.at(v.x(), v.y()).height_m);
    lowest = std::min(lowest, v.z());
  }
  EXPECT_LT(lowest, -0.5e-3);  // the relief is there, not a flat sheet
  EXPECT_EQ(mesh.vertices.front(), Eigen::Vector3d(-0.01, -0.01, mesh.vertices.front().z()));
  const TriangleBvh bvh(mesh);
  for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i) EXPECT_GT(bvh.plane(i).n.z(), 0.0) << i;
  EXPECT_THROW(srv::reliefGridMesh(surface, 0), thx::Error);
}

}  // namespace test_triangle_bvh
