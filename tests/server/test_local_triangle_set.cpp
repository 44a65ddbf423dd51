// The leaves around the pen (server/local_triangle_set.hpp): every sweep it answers is the
// hierarchy's answer to the bit (random segments in and out of its region; at a UV sphere's pole,
// where no region fits, the hierarchy's own), and a textured mesh renderer that sweeps through it renders
// the very same forces as one that asks the hierarchy every time.
#include <gtest/gtest.h>

#include <random>

#include "meshes/mesh_generators.hpp"
#include "server/local_triangle_set.hpp"
#include "server/textured_mesh_renderer.hpp"
#include "textures/generators.hpp"

namespace test_local_triangle_set {

using namespace thx;
using srv::LocalTriangleSet;
using srv::TriangleBvh;

namespace {

struct Sphere {
  mesh::GeneratedMesh generated;
  std::unique_ptr<TriangleBvh> bvh;
  Sphere(int segments, int rings)
      : generated(mesh::sphere(0.03, segments, rings, 0.01)),
        bvh(std::make_unique<TriangleBvh>(generated.mesh.positions, generated.mesh.triangles)) {}
};

// Gathers a region around p (as the renderer's ticks would, the proxy standing there).
void gatherAround(LocalTriangleSet& set, const Eigen::Vector3d& p) {
  for (int tick = 0; tick < 200 && !set.hasRegion(); ++tick) set.advance(p);
}

void expectSameAnswer(const TriangleBvh& bvh, const LocalTriangleSet& set, const Eigen::Vector3d& a,
                      const Eigen::Vector3d& b, const std::uint32_t* skip, int n_skip) {
  const TriangleBvh::Hit h = set.firstEntry(a, b, skip, n_skip), r = bvh.firstEntry(a, b, skip, n_skip);
  ASSERT_EQ(h.hit, r.hit) << a.transpose() << " -> " << b.transpose();
  if (!r.hit) return;
  EXPECT_EQ(h.t, r.t);
  EXPECT_EQ(h.triangle, r.triangle);
  EXPECT_EQ(h.point, r.point);
}

}  // namespace

TEST(LocalTriangleSet, AnswersEverySweepAsTheHierarchyDoes) {
  const Sphere s(96, 48);
  LocalTriangleSet set(*s.bvh);
  const Eigen::Vector3d p = Eigen::Vector3d(1.0, 0.3, 0.2).normalized() * 0.03;
  gatherAround(set, p);
  ASSERT_TRUE(set.hasRegion());
  EXPECT_GT(set.leaves(), 0);
  const double h = set.halfSide();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> inside(-0.95 * h, 0.95 * h), wide(-4.0 * h, 4.0 * h), u(0.0, 1.0);
  int hits = 0;
  for (int i = 0; i < 4000; ++i) {
    // Half the segments inside the region (answered locally), half reaching out of it.
    const bool local = i % 2 == 0;
    auto draw = [&] { return Eigen::Vector3d(local ? inside(rng) : wide(rng), local ? inside(rng) : wide(rng), local ? inside(rng) : wide(rng)); };
    const Eigen::Vector3d a = p + draw(), b = p + draw();
    // Now and then skip the triangle the hierarchy would answer (a held face).
    std::uint32_t skip[1] = {s.bvh->firstEntry(a, b).triangle};
    const int n_skip = u(rng) < 0.3 ? 1 : 0;
    expectSameAnswer(*s.bvh, set, a, b, skip, n_skip);
    hits += s.bvh->firstEntry(a, b).hit ? 1 : 0;
  }
  EXPECT_GT(hits, 400) << "the segments cross the surface often enough to compare entries";
  EXPECT_GT(set.localAnswers(), 1900);
  EXPECT_GT(set.hierarchyAnswers(), 1000);
}

TEST(LocalTriangleSet, WhereEveryRegionHasTooManyLeavesTheHierarchyAnswers) {
  // A UV sphere's pole, where 512 thin triangles meet: every region around it holds more than
  // kMaxLeaves leaves (their boxes all reach the pole), so the side halves down to its floor,
  // no region is kept, and every sweep there is the hierarchy's.
  const Sphere s(512, 8);
  const Eigen::Vector3d pole(0.0, 0.0, 0.03);
  LocalTriangleSet set(*s.bvh);
  const double start = set.halfSide();
  gatherAround(set, pole);
  EXPECT_FALSE(set.hasRegion());
  EXPECT_NEAR(set.halfSide(), start / 4.0, 1e-12 * start) << "halved to its floor, a quarter of the start";
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> d(-start, start);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d a = pole + Eigen::Vector3d(d(rng), d(rng), std::fabs(d(rng)));
    const Eigen::Vector3d b = pole + Eigen::Vector3d(d(rng), d(rng), -std::fabs(d(rng)));
    expectSameAnswer(*s.bvh, set, a, b, nullptr, 0);
  }
  EXPECT_EQ(set.localAnswers(), 0);
}

TEST(LocalTriangleSet, ARendererSweepingThroughItRendersTheSameForcesPreparedBeforeOrAfterTheForce) {
  // A relief-textured sphere stroked 1 mm deep along a wavy path at 50 mm/s, and a stroke that
  // leaves the surface and comes back; one renderer with the local set, one without, and one
  // with it run in the servo's order.
  const Sphere s(128, 64);
  tex::GenerateRequest request;
  request.kind = "bricks";
  request.size = 128;
  const tex::TextureMap map = tex::generate(request);
  const srv::MeshTexture texture{&map, {tex::Filter::Bilinear, tex::Address::Wrap}, map.isRelief()};
  srv::RendererConfig config;
  config.stiffness_n_per_m = 600.0;
  srv::TexturedMeshRenderer local(s.generated.mesh, *s.bvh, texture, Eigen::Isometry3d::Identity(), config);
  srv::TexturedMeshRenderer hierarchy(s.generated.mesh, *s.bvh, texture, Eigen::Isometry3d::Identity(), config);
  hierarchy.useLocalSet(false);
  // As the servo runs it: the gathering moved on after each force (prepareNextTick), not at the
  // start of the next render().
  srv::TexturedMeshRenderer servo_order(s.generated.mesh, *s.bvh, texture, Eigen::Isometry3d::Identity(), config);
  int in_contact = 0;
  for (int k = 0; k < 6000; ++k) {
    const double a = 5e-5 * k / 0.03, b = 0.3 * std::sin(a * 3.0);
    const double depth = k % 2000 < 1700 ? 1e-3 : -2e-3;  // out of contact for 300 ticks in 2000
    const Eigen::Vector3d n(std::cos(a) * std::cos(b), std::sin(a) * std::cos(b), std::sin(b));
    const Eigen::Vector3d tip = n * (0.03 - depth), v = Eigen::Vector3d(-std::sin(a), std::cos(a), 0.0) * 0.05;
    const srv::RenderOutput x = local.render(tip, v), y = hierarchy.render(tip, v), z = servo_order.render(tip, v);
    servo_order.prepareNextTick();
    ASSERT_EQ(x.in_contact, y.in_contact) << k;
    ASSERT_EQ(x.force_world, y.force_world) << k;
    ASSERT_EQ(x.proxy_world, y.proxy_world) << k;
    ASSERT_EQ(x.triangle, y.triangle) << k;
    ASSERT_EQ(z.force_world, x.force_world) << k;
    ASSERT_EQ(z.proxy_world, x.proxy_world) << k;
    in_contact += x.in_contact ? 1 : 0;
  }
  EXPECT_GT(in_contact, 3000);
  EXPECT_GT(local.localSet().localAnswers(), 10 * local.localSet().hierarchyAnswers())
      << "the sweeps are answered from the leaves around the pen";
  EXPECT_EQ(servo_order.localSet().localAnswers(), local.localSet().localAnswers());
  EXPECT_EQ(servo_order.localSet().gathers(), local.localSet().gathers());
}

}  // namespace test_local_triangle_set
