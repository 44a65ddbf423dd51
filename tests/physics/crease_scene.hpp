#pragma once
// A block by a crease of a mesh (chart_boundary.hpp): a 2 x 2 x 1 cm block (grooved_block_scene.hpp)
// on the top of a slab mesh (a ridge of its V-grooves on the slab's edge at x = 0.1 m, its top at
// z = 0), its centre some way short of the edge or past it; the slab grooved, or untextured and met
// on its smooth chart or on Bullet's triangles. The block plain (resting on the ridges) or grooved
// like the slab (its ridges down in the slab's grooves). Shared by
// tests/physics/test_object_across_a_crease.cpp and benchmarks/bench_object_by_crease.cpp.
#include <algorithm>
#include <cmath>
#include <memory>

#include "tests/physics/grooved_block_scene.hpp"

namespace thx::phys::test::crease {

using namespace grooved_block;

inline constexpr double kEdge = 0.1;  // the slab's edge (x), its top at z = 0

// The grooved relief, the same mesh untextured met on its smooth chart, or on Bullet's triangles.
enum class Ground { Grooved, Smooth, Triangles };

inline MeshContactOptions untextured(Ground ground) {
  MeshContactOptions options;
  options.smooth_chart = ground == Ground::Smooth;
  return options;
}

struct Tip {
  double pitch_30ms = 0.0, pitch_60ms = 0.0;  // rad, about the edge (y)
  double fastest_x = 0.0;                     // m/s, the centre's largest speed along x
  double moved_m = 0.0;                       // the centre's travel over the run
  double drift_m = 0.0;                       // its travel from 0.1 s to the end
};

struct CreaseScene {
  mesh::GeneratedMesh slab = groovedGround(false);
  tex::TextureMap map = heightMap(128, kExtent, vGrooves);
  std::unique_ptr<PhysicsWorld> world = std::make_unique<PhysicsWorld>();
  btRigidBody* block = nullptr;

  // The block's centre `beyond` past the edge. Plain: at rest on the ridges (its underside on
  // z = 0). Grooved: its ridges over the slab's grooves, 0.2 mm above where they fit (`beyond` then
  // puts its centre over a groove: 2 mm either side of the edge).
  CreaseScene(double beyond, Ground ground, bool grooved_block) {
    if (ground == Ground::Grooved) {
      addGroovedGround(*world, slab, false, map);
    } else {
      world->addTexturedMesh(slab.mesh, at(0.0, 0.0, -0.01), {1.0, 0.0, 0.0}, untextured(ground));
    }
    FaceTexture faces;
    faces.map = &map;
    faces.tile_m = kExtent;
    block = grooved_block ? &world->addTexturedBox(kHalf, kMass, at(kEdge + beyond, 0.0, kHalf.z() - kDepth + 2e-4),
                                                   {kFriction, 0.0, 0.0}, faces)
                          : &world->addBox(kHalf, kMass, at(kEdge + beyond, 0.0, kHalf.z() + 1e-6), {kFriction, 0.0, 0.0});
  }

  // Released from rest for `seconds`.
  Tip run(double seconds) {
    const Eigen::Vector3d start = positionOf(*block);
    Eigen::Vector3d settled = start;
    Tip tip;
    for (int k = 1; k <= int(std::lround(seconds / kDt)); ++k) {
      world->step(kDt);
      tip.fastest_x = std::max(tip.fastest_x, std::fabs(double(block->getLinearVelocity().x())));
      if (k == 100) settled = positionOf(*block);
      btScalar yaw, pitch, roll;
      block->getWorldTransform().getBasis().getEulerZYX(yaw, pitch, roll);
      if (k == 30) tip.pitch_30ms = double(pitch);
      if (k == 60) tip.pitch_60ms = double(pitch);
    }
    tip.moved_m = (positionOf(*block) - start).norm();
    tip.drift_m = (positionOf(*block) - settled).norm();
    return tip;
  }
};

inline Tip release(double beyond, Ground ground, double seconds, bool grooved_block = false) {
  return CreaseScene(beyond, ground, grooved_block).run(seconds);
}

// The plain block pivoting from rest about the edge under its underside, without slipping: the
// pitch at time t (RK4 at 0.1 ms). Its centre lies d past the pivot and half its height h above it.
inline double pivotPitch(double d, double t) {
  const double a = kHalf.x(), h = kHalf.z(), r = std::hypot(d, h), phi0 = std::atan2(d, h);
  const double k = kG * r / ((a * a + h * h) / 3.0 + r * r);  // torque / inertia about the edge, per sin
  double theta = 0.0, omega = 0.0;
  const double dt = 1e-4;
  auto alpha = [&](double th) { return k * std::sin(phi0 + th); };
  for (int n = 0; n < int(std::lround(t / dt)); ++n) {
    const double k1t = omega, k1w = alpha(theta);
    const double k2t = omega + 0.5 * dt * k1w, k2w = alpha(theta + 0.5 * dt * k1t);
    const double k3t = omega + 0.5 * dt * k2w, k3w = alpha(theta + 0.5 * dt * k2t);
    const double k4t = omega + dt * k3w, k4w = alpha(theta + dt * k3t);
    theta += dt / 6.0 * (k1t + 2 * k2t + 2 * k3t + k4t);
    omega += dt / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
  }
  return theta;
}

}  // namespace thx::phys::test::crease
