#pragma once
// A ball with a bump map on a mesh (issue 29; clients/physics/textured_ball.hpp, met on the mesh's
// chart: mesh_relief_chart.hpp): a ball recessed by kRecess everywhere rolls on its recessed
// radius rho with the whole ball's inertia, so it swings in a smooth bowl and leaves the top of a
// smooth sphere as the rigid-ball answers say for rho and k = 2 r^2 / (5 rho^2); and the bumpy ball
// of textured_ball_scene.hpp let down on a slab mesh. Shared by
// tests/physics/test_textured_ball_on_mesh.cpp and benchmarks/bench_textured_ball.cpp.
#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <vector>

#include "tests/physics/mesh_rolling_scenes.hpp"
#include "tests/physics/textured_ball_scene.hpp"

namespace thx::phys::test::textured_ball_on_mesh {

inline constexpr double kRecess = 2e-3;  // rho = 8 mm under the 1 cm ball
inline constexpr double kRho = textured_ball::kRadius - kRecess;
// Rolling on rho with the whole ball's inertia: kinetic energy (1 + k) m v^2 / 2.
inline constexpr double kInertiaRatio =
    2.0 * textured_ball::kRadius * textured_ball::kRadius / (5.0 * kRho * kRho);

// T = 2 pi sqrt((R - rho)(1 + k) / g), with the pendulum's correction at theta0.
inline double recessedSwingAnswer(double bowl_radius, double theta0_deg) {
  const double t2 = deg(theta0_deg) * deg(theta0_deg);
  return 2.0 * kPi * std::sqrt((bowl_radius - kRho) * (1.0 + kInertiaRatio) / kG) * (1.0 + t2 / 16.0 + 11.0 * t2 * t2 / 3072.0);
}
// cos(theta) = 2 cos(theta0) / (3 + k), degrees.
inline double recessedDepartureAnswer(double theta0_deg) {
  return std::acos(2.0 * std::cos(deg(theta0_deg)) / (3.0 + kInertiaRatio)) * 180.0 / kPi;
}

struct MeshRun {
  double value = 0.0;         // the period (s) or the departure (degrees)
  double us_per_step = 0.0;   // wall clock, the whole step
};

// Released at rest theta0 (degrees) down the inside of a smooth UV sphere of radius R (the bowl,
// `segments` around), friction 1: the period from its crossings of the bottom moving in +x.
inline MeshRun recessedSwing(double bowl_radius, double theta0_deg, double seconds, int segments = 128) {
  namespace ball = textured_ball;
  const tex::TextureMap recess = ball::uniformRecess(kRecess);
  const FaceTexture texture = ball::ballTexture(recess);
  mesh_rolling::SphereScene scene(segments, true, bowl_radius);
  const double l = bowl_radius - kRho, th = deg(theta0_deg);
  btRigidBody& b = scene.world.addTexturedSphere(ball::kRadius, ball::kMass,
                                                 mesh_rolling::placedAt({l * std::sin(th), 0.0, -l * std::cos(th)}),
                                                 {1.0, 0.0, 0.0}, texture);
  std::vector<double> crossings;
  double x_last = positionOf(b).x();
  const int steps = int(std::lround(seconds / ball::kDt));
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 1; k <= steps; ++k) {
    scene.world.step(ball::kDt);
    const double x = positionOf(b).x();
    if (x_last < 0.0 && x >= 0.0) crossings.push_back(ball::kDt * (k - 1 + (-x_last) / (x - x_last)));
    x_last = x;
  }
  MeshRun run;
  run.us_per_step = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / steps;
  if (crossings.size() >= 2) run.value = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  return run;
}

// Rolled from rest theta0 (degrees) off the top of a UV sphere of radius R (`segments` around),
// friction 10 (with 1 the ball slips as its load vanishes, and leaves early): the angle from the
// top (degrees) of the last step that pushed it. With `relief`, laid on the sphere (a relief
// chart), else its smooth chart.
inline MeshRun recessedDeparture(double sphere_radius, double theta0_deg, const tex::TextureMap* relief,
                                 int segments = 128) {
  namespace ball = textured_ball;
  const tex::TextureMap recess = ball::uniformRecess(kRecess);
  const FaceTexture texture = ball::ballTexture(recess);
  mesh_rolling::SphereScene scene(segments, true, sphere_radius, relief);
  const double l = sphere_radius + kRho, th = deg(theta0_deg);
  const Eigen::Vector3d dir(std::cos(0.3), std::sin(0.3), 0.0);  // off the rings of vertices
  btRigidBody& b = scene.world.addTexturedSphere(
      ball::kRadius, ball::kMass,
      mesh_rolling::placedAt(l * (std::sin(th) * dir + std::cos(th) * Eigen::Vector3d::UnitZ())), {10.0, 0.0, 0.0},
      texture);
  MeshRun run;
  int steps = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 1; k <= 3000; ++k, ++steps) {
    scene.world.step(ball::kDt);
    const Eigen::Vector3d c = positionOf(b);
    const double theta = std::atan2(std::hypot(c.x(), c.y()), c.z()) * 180.0 / kPi;
    if (mesh_rolling::normalImpulse(scene.world, b) > 0.0) run.value = theta;
    else if (theta > 90.0) break;
  }
  run.us_per_step = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / steps;
  return run;
}

// The bumpy ball of settleBumpyBall (textured_ball_scene.hpp), let down the same way onto the top
// of a slab mesh (20 cm square, its top at z = 0) carrying `relief` at one tile per 4 cm, as the
// relief plane carries it there: its height and the fastest it moved over the last 0.5 s.
inline textured_ball::Settled settleOnSlab(const tex::TextureMap& relief, double seconds) {
  namespace ball = textured_ball;
  const tex::TextureMap map = ball::bumpMap(3e-4);
  const FaceTexture texture = ball::ballTexture(map);
  const mesh::GeneratedMesh slab = mesh::box({0.2, 0.2, 0.02}, 0.02, 0.04);
  PhysicsWorld world;
  MeshContactOptions options;
  options.texture = &relief;
  options.normals_made_for_m = Eigen::Vector2d::Constant(0.04);
  world.addTexturedMesh(slab.mesh, at(0.0, 0.0, -0.01), {0.5, 0.0, 0.0}, options);
  Eigen::Isometry3d pose = at(0.001, 0.0, ball::kRadius + 2e-4);
  pose.linear() = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()))
                      .toRotationMatrix();
  btRigidBody& b = world.addTexturedSphere(ball::kRadius, ball::kMass, pose, {0.5, 0.0, 0.0}, texture);
  const int steps = int(std::lround(seconds / ball::kDt));
  ball::Settled s;
  for (int k = 0; k < steps; ++k) {
    world.step(ball::kDt);
    if (k >= steps - 500) s.fastest = std::max(s.fastest, velocityOf(b).norm());
  }
  s.centre = positionOf(b);
  s.height = s.centre.z();
  return s;
}

}  // namespace thx::phys::test::textured_ball_on_mesh
