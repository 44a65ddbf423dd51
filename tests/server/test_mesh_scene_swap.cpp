// A scene switch between the plane and a textured mesh (servo.hpp: the mesh scene's renderer,
// built off the servo thread, renders instead of the plane's until the next swap). Under contact
// the force ramps down, the servo takes the mesh's renderer at zero force and allocates nothing
// doing it; a pen that is inside the new mesh's solid at the swap feels nothing until it leaves
// (no force can jump in), and on the way back down it meets the mesh with the mesh's spring; a
// swap back gives the plane its renderer again.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "meshes/mesh_generators.hpp"
#include "server/mesh_scene.hpp"
#include "tests/server/servo_fixture.hpp"
#include "tests/support/allocation_counter.hpp"

namespace test_mesh_scene_swap {

using namespace thx;

namespace {

constexpr double kRadius = 0.05;
constexpr double kTop = -0.002;  // the sphere's highest point, on the pen's line (x = y = 0)

// Ticks 0-999: into the rig's V-valley as tests/server/test_scene_swap.cpp does (2 mm below its
// floor, 5.46 mm below z = 0 from tick 547). The switch happens while it stays there (to 1499),
// 3.46 mm inside the sphere. Then up to 5 mm above z = 0 by tick 1700, down to 2 mm below the
// sphere's top by tick 2000, held there.
void script(std::int64_t tick, dev::DeviceState& s) {
  const double floor = -test::kRigValleyDepth;
  const double low = floor - 0.002, high = 0.005, press = kTop - 0.002;
  double z = 0.0;
  double vz = 0.0;
  if (tick < 1500) {
    z = std::max(floor + 0.001 - 0.01 * double(tick) * 1e-3, low);
    vz = z > low ? -0.01 : 0.0;
  } else if (tick < 1700) {
    z = low + (high - low) * double(tick - 1500) / 200.0;
    vz = (high - low) / 0.2;
  } else if (tick < 2000) {
    z = high + (press - high) * double(tick - 1700) / 300.0;
    vz = (press - high) / 0.3;
  } else {
    z = press;
  }
  s.p_world = Eigen::Vector3d(test::kRigFloorX, 0.0, z);
  s.v_world = Eigen::Vector3d(0.0, 0.0, vz);
}

// The mesh scene: a sphere on its side (its poles along x, so the pen meets a regular part of the
// mesh), a flat normal map wrapped on it, rendered at 1000 N/m like the plane.
struct SphereScene {
  SphereScene() : texture(flat(), /*relief=*/false) {
    scene::SceneMesh built;
    built.mesh = mesh::sphere(kRadius, 64, 32, 0.02).mesh;
    built.mesh_to_world = Eigen::Translation3d(0.0, 0.0, kTop - kRadius) *
                          Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY());
    built.tile_m = {0.02, 0.02};
    geometry = std::make_shared<const srv::MeshGeometry>(std::move(built));
    config.stiffness_n_per_m = 1000.0;
    renderer = srv::buildMeshRenderer(*geometry, *texture.surface, config);
    swap.surface = texture.surface.get();
    swap.renderer = config;
    swap.stored_energy_stiffness_n_per_m = 1000.0;
    swap.mesh = renderer.get();
  }
  static tex::GenerateRequest flat() {
    tex::GenerateRequest g;
    g.kind = "tilted";
    g.size = 64;
    g.params = {{"angle_deg", 0.0}, {"direction_deg", 0.0}, {"extent", 0.02}};
    return g;
  }
  test::GeneratedSurface texture;
  srv::RendererConfig config;
  std::shared_ptr<const srv::MeshGeometry> geometry;
  std::unique_ptr<srv::TexturedMeshRenderer> renderer;
  srv::SurfaceSwap swap;
};

Eigen::Vector3d vec(const double (&v)[3]) { return {v[0], v[1], v[2]}; }

}  // namespace

TEST(MeshSceneSwap, ThePlaneHandsOverToTheMeshAtZeroForceWithoutAllocating) {
  test::ServoRig rig(script);
  rig.run(1000);
  EXPECT_NEAR(rig.safety().lastOutput().norm(), 2.0, 0.05);  // the valley's force
  SphereScene sphere;
  ASSERT_TRUE(rig.servo().surfaceSwap().offer(&sphere.swap));

  const long a0 = test::t_allocations, f0 = test::t_frees;
  double max_step = 0.0, max_inside = 0.0;
  Eigen::Vector3d prev = rig.safety().lastOutput();
  std::int64_t swapped_at = -1;
  for (int k = 1000; k < 1500; ++k) {
    const srv::TickRecord& r = rig.tick();
    const Eigen::Vector3d f = vec(r.f_out);
    max_step = std::max(max_step, (f - prev).norm());
    prev = f;
    if (r.scene_swaps == 1 && swapped_at < 0) swapped_at = k;
    if (swapped_at >= 0) max_inside = std::max(max_inside, f.norm());
    rig.drain();
  }
  EXPECT_EQ(test::t_allocations - a0, 0);
  EXPECT_EQ(test::t_frees - f0, 0);
  EXPECT_EQ(swapped_at, 1199);  // at the end of the 200-tick ramp down
  EXPECT_EQ(rig.servo().meshRenderer(), sphere.renderer.get());
  EXPECT_LT(max_step, 0.03);  // the ramp's smoothstep, no jump
  // 3.46 mm inside the sphere at the swap: no proxy is made up for a pen inside a solid.
  EXPECT_EQ(max_inside, 0.0);
  EXPECT_TRUE(rig.servo().surfaceSwap().reclaim());
}

TEST(MeshSceneSwap, AfterLeavingThePenMeetsTheMeshWithItsSpringAndASwapBackRestoresThePlane) {
  test::ServoRig rig(script);
  rig.run(1000);
  SphereScene sphere;
  ASSERT_TRUE(rig.servo().surfaceSwap().offer(&sphere.swap));
  rig.run(1500);  // to tick 2500: out, and down 2 mm into the sphere's top, held for 0.5 s
  const srv::TickRecord& r = rig.tickAndDrain();
  ASSERT_TRUE(r.in_contact);
  // The spring of 1000 N/m over 2 mm, straight up (the sphere's normal at its top).
  EXPECT_NEAR(vec(r.f_render).z(), 2.0, 0.02);
  EXPECT_NEAR(vec(r.f_render).head<2>().norm(), 0.0, 0.02);
  EXPECT_NEAR(vec(r.proxy_world).z(), kTop, 2e-5);
  ASSERT_TRUE(rig.servo().surfaceSwap().reclaim());

  // And back to a plane scene: the rig's own valley surface.
  srv::SurfaceSwap plane;
  plane.surface = rig.texture.surface.get();
  plane.renderer = rig.config().renderer;
  plane.stored_energy_stiffness_n_per_m = rig.config().renderer.stiffness_n_per_m;
  ASSERT_TRUE(rig.servo().surfaceSwap().offer(&plane));
  rig.run(450);
  EXPECT_EQ(rig.servo().meshRenderer(), nullptr);
  EXPECT_EQ(&rig.renderer().surface(), rig.texture.surface.get());
  EXPECT_TRUE(rig.servo().surfaceSwap().reclaim());
}

}  // namespace test_mesh_scene_swap
