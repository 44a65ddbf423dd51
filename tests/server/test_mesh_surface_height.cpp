// MeshSurfaceHeight: a generated sphere's heights seen from above within its tessellation error
// (and never above the sphere: the flat triangles are inside it), nothing off its footprint, its
// top; a bowl felt from above on its inside floor; and the simulated PHANToM pressing on a sphere
// mesh through it (its hand's target at the press is on the mesh, and its ticks allocate
// nothing: this file counts allocations, so it runs in server_counted_tests).
#include <gtest/gtest.h>

#include "tests/support/allocation_counter.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "base/error.hpp"
#include "device/sim_phantom.hpp"
#include "meshes/mesh_generators.hpp"
#include "server/mesh_surface_height.hpp"
#include "server/textured_mesh_renderer.hpp"
#include "server/triangle_bvh.hpp"

namespace test_mesh_surface_height {

using namespace thx;
using srv::MeshSurfaceHeight;

namespace {

// A generated mesh and its hierarchy (the hierarchy points at the mesh's arrays: built in place).
struct Shape {
  explicit Shape(const mesh::TexturedMesh& m) : mesh(m), bvh(mesh.positions, mesh.triangles) {}
  mesh::TexturedMesh mesh;
  srv::TriangleBvh bvh;
};

// The largest vertical gap between a sphere of radius r and an inscribed UV sphere mesh whose
// quads span at most `delta` radians, where the surface's normal is within acos(cos_tilt) of the
// vertical: the radial sag r (1 - cos delta), over cos_tilt.
double sphereSag(double r, int segments, int rings, double cos_tilt) {
  const double delta = std::max(2 * std::numbers::pi / segments, std::numbers::pi / rings);
  return r * (1 - std::cos(delta)) / cos_tilt;
}

}  // namespace

TEST(MeshSurfaceHeight, SphereHeightsWithinTheTessellationAndNothingOffTheFootprint) {
  constexpr double kR = 0.03;
  constexpr int kSegments = 48, kRings = 24;
  const Shape sphere(mesh::sphere(kR, kSegments, kRings, 0.01).mesh);
  Eigen::Isometry3d mesh_to_script = Eigen::Isometry3d::Identity();
  mesh_to_script.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 1, 0.3).normalized()).toRotationMatrix();
  mesh_to_script.translation() = Eigen::Vector3d(0.004, -0.006, -0.012);
  const MeshSurfaceHeight height(sphere.bvh, mesh_to_script);
  const Eigen::Vector3d c = mesh_to_script.translation();

  // Its highest and lowest vertices: within a quad's sag of the sphere's.
  const double cos_delta = std::cos(std::max(2 * std::numbers::pi / kSegments, std::numbers::pi / kRings));
  EXPECT_LE(height.top(), c.z() + kR + 1e-15);
  EXPECT_GE(height.top(), c.z() + kR * cos_delta);
  EXPECT_GE(height.bottom(), c.z() - kR - 1e-15);
  EXPECT_LE(height.bottom(), c.z() - kR * cos_delta);

  // Within 0.8 R of the axis the surface's normal is within acos(0.6) of the vertical.
  const double tolerance = sphereSag(kR, kSegments, kRings, 0.6);
  double worst = 0.0;
  int inside = 0, outside = 0;
  for (int i = 0; i <= 40; ++i) {
    for (int j = 0; j <= 40; ++j) {
      const Eigen::Vector2d d(1.2 * kR * (i / 20.0 - 1.0), 1.2 * kR * (j / 20.0 - 1.0));
      const Eigen::Vector2d xy = c.head<2>() + d;
      double z = -1.0;
      const bool found = height.heightAt(xy, z);
      if (d.norm() <= 0.8 * kR) {
        ++inside;
        ASSERT_TRUE(found) << d.transpose();
        const double exact = c.z() + std::sqrt(kR * kR - d.squaredNorm());
        ASSERT_LE(z, exact + 1e-12) << d.transpose();  // the flat triangles are inside the sphere
        ASSERT_LE(exact - z, tolerance) << d.transpose();
        worst = std::max(worst, exact - z);
      } else if (d.norm() >= 1.001 * kR) {
        ++outside;
        ASSERT_FALSE(found) << d.transpose();
        ASSERT_EQ(z, -1.0);  // untouched
      }
    }
  }
  EXPECT_GT(inside, 500);  // ~ pi 0.8^2 / 0.06^2 points
  EXPECT_GT(outside, 300);
  EXPECT_GT(worst, 0.0);
  std::printf("sphere r %g m, %d x %d: worst height error %.3g m (bound %.3g m)\n", kR, kSegments, kRings, worst,
              tolerance);
}

TEST(MeshSurfaceHeight, UprightSphereTopIsItsPoleAndNonFinitePointsFindNothing) {
  constexpr double kR = 0.02;
  const Shape sphere(mesh::sphere(kR, 32, 16, 0.01).mesh);
  const Eigen::Isometry3d mesh_to_script(Eigen::Translation3d(0.01, 0.02, -0.015));
  const MeshSurfaceHeight height(sphere.bvh, mesh_to_script);
  EXPECT_NEAR(height.top(), -0.015 + kR, 1e-15);
  EXPECT_NEAR(height.bottom(), -0.015 - kR, 1e-15);
  double z = 0.0;
  ASSERT_TRUE(height.heightAt({0.01, 0.02}, z));  // through the pole vertex, shared by 32 faces
  EXPECT_NEAR(z, height.top(), 1e-15);
  EXPECT_FALSE(height.heightAt({std::nan(""), 0.02}, z));
  EXPECT_FALSE(height.heightAt({0.01, std::numeric_limits<double>::infinity()}, z));

  Eigen::Isometry3d sheared = Eigen::Isometry3d::Identity();
  sheared.linear()(0, 1) = 0.5;
  EXPECT_THROW(MeshSurfaceHeight(sphere.bvh, sheared), thx::Error);
}

TEST(MeshSurfaceHeight, BowlIsSeenFromAboveOnItsInsideFloor) {
  constexpr double kRadius = 0.05, kHeight = 0.04, kWall = 0.004;
  const Shape bowl(mesh::lathe(mesh::bowlProfile(kRadius, kHeight, kWall, 24), 64, 0.01).mesh);
  const Eigen::Isometry3d mesh_to_script(Eigen::Translation3d(0.0, 0.0, -kHeight));  // the rim at z = 0
  const MeshSurfaceHeight height(bowl.bvh, mesh_to_script);
  EXPECT_NEAR(height.top(), kWall / 2, 1e-12);  // the rounded rim's crest
  double z = 0.0;
  ASSERT_TRUE(height.heightAt({0.0, 0.0}, z));
  EXPECT_NEAR(z, -kHeight + kWall, 1e-12);  // the inside floor's centre, not the outside bottom
  // Inside: z = wall + (H - wall)(1 - cos t) at r = (R - wall) sin t (mesh_generators.cpp).
  double worst = 0.0;
  for (double r : {0.005, 0.015, 0.025, 0.035}) {
    for (double phi : {0.1, 1.3, 2.9, 4.4}) {
      const Eigen::Vector2d xy(r * std::cos(phi), r * std::sin(phi));
      ASSERT_TRUE(height.heightAt(xy, z)) << r << " " << phi;
      const double s = r / (kRadius - kWall);
      const double inside = -kHeight + kWall + (kHeight - kWall) * (1 - std::sqrt(1 - s * s));
      EXPECT_NEAR(z, inside, 2e-4) << r << " " << phi;  // the wall is 4e-3
      worst = std::max(worst, std::abs(z - inside));
    }
  }
  std::printf("bowl: worst inside height error %.3g m\n", worst);
  EXPECT_FALSE(height.heightAt({kRadius + 0.001, 0.0}, z));
}

// The simulated PHANToM pressing on a sphere mesh placed in the world, its script in the surface
// pose's frame, the sphere rendered to the pen as a spring by the "servo" below.
TEST(MeshSurfaceHeight, SimPhantomPressesOnASphereThroughItsHeights) {
  constexpr double kR = 0.04, kStiffness = 500.0, kPushN = 1.0;
  const Shape sphere(mesh::sphere(kR, 48, 24, 0.01).mesh);
  Eigen::Isometry3d plane_to_world = Eigen::Isometry3d::Identity();
  plane_to_world.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()).toRotationMatrix();
  plane_to_world.translation() = Eigen::Vector3d(0.01, 0.0, 0.02);
  const Eigen::Vector3d centre_local(0.0, 0.0, -0.03);  // the sphere's top 1 cm above the frame's z = 0
  const Eigen::Isometry3d mesh_to_world =
      plane_to_world * Eigen::Translation3d(centre_local) * Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ());
  const MeshSurfaceHeight height(sphere.bvh, plane_to_world.inverse() * mesh_to_world);
  EXPECT_NEAR(height.top(), 0.01, 1e-12);

  const Eigen::Vector2d press(0.01, 0.005);
  const dev::HandScript script({dev::HandPress{press, kPushN, 0.4}});
  dev::SimPhantomConfig config;
  config.plane_to_world = plane_to_world;
  config.surface_height = &height;
  dev::SimPhantom sim(config, script);
  sim.open();
  const Eigen::Isometry3d world_to_plane = plane_to_world.inverse();
  const Eigen::Vector3d start_target = world_to_plane * sim.truth().hand_target_world.p_m;
  EXPECT_NEAR(start_target.z(), height.top() + script.options().hover_height_m, 1e-12);

  double h_press = 0.0;
  ASSERT_TRUE(height.heightAt(press, h_press));
  const double exact = centre_local.z() + std::sqrt(kR * kR - press.squaredNorm());
  EXPECT_LE(h_press, exact + 1e-12);
  EXPECT_LE(exact - h_press, sphereSag(kR, 48, 24, 0.9));

  const dev::HandScriptOptions& o = script.options();
  const double settled_s = o.approach_s + o.force_ramp_s + 0.3;  // late in the press
  bool checked = false;
  long allocations = 0;
  while (sim.truth().t_s < script.duration()) {
    const long before = thx::test::g_allocations.load();
    const dev::DeviceState s = sim.read();
    // The servo: a spring out of the analytic sphere, from the reading.
    const Eigen::Vector3d d = world_to_plane * s.p_world - centre_local;
    const double depth = kR - d.norm();
    dev::DeviceCommand cmd;
    cmd.forces_enabled = true;
    if (depth > 0.0) cmd.force_world_n = plane_to_world.linear() * (kStiffness * depth * d.normalized());
    sim.write(cmd);
    allocations += thx::test::g_allocations.load() - before;
    if (!checked && sim.truth().t_s >= settled_s) {
      checked = true;
      const Eigen::Vector3d target = world_to_plane * sim.truth().hand_target_world.p_m;
      EXPECT_NEAR(target.x(), press.x(), 1e-12);
      EXPECT_NEAR(target.y(), press.y(), 1e-12);
      EXPECT_NEAR(target.z(), h_press, 1e-12);  // the hand's target reached the surface's height
      EXPECT_EQ(s.buttons, 1u);
      // The pen rests on the sphere, pushed in by about the push over the stiffness, under the press.
      const Eigen::Vector3d pen = world_to_plane * sim.truth().p_world_m;
      const double pen_depth = kR - (pen - centre_local).norm();
      EXPECT_GT(pen_depth, 0.5 * kPushN / kStiffness);
      EXPECT_LT(pen_depth, 2.0 * kPushN / kStiffness);
      EXPECT_LT((pen.head<2>() - press).norm(), 2e-3);  // the slope's pull on the hand's spring: ~1 mm
      std::printf("press: target z %.6f m (exact sphere %.6f m), pen depth %.3g m, pen off the point %.3g m\n",
                  target.z(), exact, pen_depth, (pen.head<2>() - press).norm());
    }
  }
  EXPECT_TRUE(checked);
  EXPECT_EQ(allocations, 0);  // the height queries included
}

}  // namespace test_mesh_surface_height
