// The textured meshes' CPU visibility (clients/visual/mesh_ray_caster.hpp): the hierarchy finds
// the same first front face as a test of every triangle, on a torus (a ray meets it up to four
// times, front and back faces), and never a back face.
#include <gtest/gtest.h>

#include <random>

#include "clients/visual/mesh_ray_caster.hpp"
#include "meshes/mesh_generators.hpp"

namespace thx::visual::test_mesh_ray_caster {
namespace {

// Every triangle, the same front-face test as the caster.
std::optional<MeshRayHit> bruteForce(const mesh::TexturedMesh& m, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  std::optional<MeshRayHit> best;
  for (std::uint32_t k = 0; k < m.triangles.size(); ++k) {
    const Eigen::Vector3d &a = m.positions[m.triangles[k][0]], &b = m.positions[m.triangles[k][1]],
                          &c = m.positions[m.triangles[k][2]];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.dot(d) >= 0) continue;
    const double t = n.dot(a - o) / n.dot(d);
    if (t <= 0 || (best && t >= best->t)) continue;
    const Eigen::Vector3d p = o + t * d;
    const double wa = (b - p).cross(c - p).dot(n), wb = (c - p).cross(a - p).dot(n), wc = (a - p).cross(b - p).dot(n);
    if (wa < 0 || wb < 0 || wc < 0) continue;
    best = MeshRayHit{k, Eigen::Vector3d(wa, wb, wc) / n.squaredNorm(), t};
  }
  return best;
}

TEST(VisualMeshRayCaster, SameFirstFrontFaceAsEveryTriangleTested) {
  const mesh::GeneratedMesh torus = mesh::torus(0.05, 0.02, 48, 24, 0.05);
  const MeshRayCaster caster(torus.mesh);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int hits = 0;
  for (int k = 0; k < 400; ++k) {  // 400: a few seconds in the Debug sanitizer tree
    const Eigen::Vector3d o = Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized() * 0.15;
    const Eigen::Vector3d target(0.07 * unit(rng), 0.07 * unit(rng), 0.02 * unit(rng));
    const Eigen::Vector3d d = (target - o).normalized();
    const auto expected = bruteForce(torus.mesh, o, d);
    const auto got = caster.firstHit(o, d);
    ASSERT_EQ(got.has_value(), expected.has_value()) << "ray " << k;
    if (!got) continue;
    ++hits;
    // A ray through a shared edge may name either triangle: the point and its distance agree.
    EXPECT_NEAR(got->t, expected->t, 1e-12) << "ray " << k;
    const mesh::Triangle& t = torus.mesh.triangles[got->triangle];
    const Eigen::Vector3d p = got->barycentric.x() * torus.mesh.positions[t[0]] +
                              got->barycentric.y() * torus.mesh.positions[t[1]] +
                              got->barycentric.z() * torus.mesh.positions[t[2]];
    EXPECT_LT((p - (o + got->t * d)).norm(), 1e-12) << "ray " << k;
    const Eigen::Vector3d n = (torus.mesh.positions[t[1]] - torus.mesh.positions[t[0]])
                                  .cross(torus.mesh.positions[t[2]] - torus.mesh.positions[t[0]]);
    EXPECT_LT(n.dot(d), 0.0) << "a back face, ray " << k;
  }
  EXPECT_GT(hits, 100);
}

TEST(VisualMeshRayCaster, RayFromInsideAClosedMeshMeetsNothing) {
  // Inside a sphere every face turns its back to the eye (the rasteriser culls them all).
  const mesh::GeneratedMesh s = mesh::sphere(0.05, 32, 16, 0.05);
  const MeshRayCaster caster(s.mesh);
  EXPECT_FALSE(caster.firstHit(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.3, 0.2, 0.9).normalized()));
  EXPECT_TRUE(caster.firstHit(Eigen::Vector3d(0, 0, 0.2), Eigen::Vector3d(0, 0.01, -1).normalized()));
}

}  // namespace
}  // namespace thx::visual::test_mesh_ray_caster
