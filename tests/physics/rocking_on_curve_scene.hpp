#pragma once
// Objects rocking on a smooth curved mesh, untextured (issue 29: boxes and rods on a curved
// surface meet the surface the mesh stands for, mesh_relief_chart.hpp's smooth chart), against
// the exact rolling answer:
//  - a block (2 x 2 x 1 cm) on top of a horizontal cylinder of radius R = 5 cm, rocking across
//    it: rolling without slipping, its centre height is (R + h) cos t + R t sin t and its
//    contact point (the instant centre) lies sqrt(h^2 + (R t)^2) from the centre, h its half
//    height (stable for h < R; small swings at 2 pi sqrt((I/m + h^2) / (g (R - h))));
//  - a rod (a capsule or a cylinder, radius r = 6 mm) lying along the inside of a pipe of radius
//    R = 5 cm, rolling across its floor: 2 pi sqrt((R - r)(1 + I / (m r^2)) / g) for small swings,
//    I the body's own moment about its axis (Bullet's, as the solver has it).
// The swing's period is read from the roll angle's upward zero crossings and compared with the
// rolling equations integrated at 0.1 ms (rollingPeriod); the scene steps 1 ms unless given. Shared by
// tests/physics/test_objects_on_smooth_mesh.cpp and benchmarks/bench_rocking_on_curve.cpp.
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <functional>
#include <vector>

#include "clients/physics/bullet_convert.hpp"
#include "clients/physics/physics_world.hpp"
#include "meshes/mesh_generators.hpp"
#include "tests/physics/physics_fixtures.hpp"

namespace thx::phys::test::rocking_on_curve {

inline constexpr double kCurveRadius = 0.05, kLength = 0.1, kDt = 1e-3, kFriction = 1.0;
inline const Eigen::Vector3d kBlockHalf(0.01, 0.01, 0.005);  // rocks about x: across y, h along z
inline constexpr double kBlockMass = 0.03, kRodRadius = 0.006, kRodHalfLength = 0.02, kRodMass = 0.03;

// How the mesh meets the object: on its smooth chart (the product), or Bullet's triangles (their
// normals steered to the interpolated one; the baseline).
enum class Contact { SmoothChart, Triangles };
enum class Rocker { Block, Capsule, Cylinder };

// The rolling equations in the roll angle t, with the moment about the instant centre J(t) and the
// potential's slope U'(t) per unit mass: J t'' + J'(t) t'^2 / 2 + U'(t) = 0 (a Lagrangian of
// one coordinate). The period of a swing released from rest at t0, by RK4 at `dt`.
inline double rollingPeriod(const std::function<double(double)>& j, const std::function<double(double)>& dj,
                            const std::function<double(double)>& du, double t0, double dt = 1e-4) {
  double t = t0, w = 0.0, time = 0.0;
  auto accel = [&](double a, double b) { return -(du(a) + 0.5 * dj(a) * b * b) / j(a); };
  int crossings = 0;
  double first = 0.0;
  for (int n = 0; n < 10'000'000; ++n) {
    const double k1t = w, k1w = accel(t, w);
    const double k2t = w + 0.5 * dt * k1w, k2w = accel(t + 0.5 * dt * k1t, w + 0.5 * dt * k1w);
    const double k3t = w + 0.5 * dt * k2w, k3w = accel(t + 0.5 * dt * k2t, w + 0.5 * dt * k2w);
    const double k4t = w + dt * k3w, k4w = accel(t + dt * k3t, w + dt * k3w);
    const double t_next = t + dt / 6.0 * (k1t + 2 * k2t + 2 * k3t + k4t);
    w += dt / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
    if (t < 0.0 && t_next >= 0.0) {
      const double at = time + dt * (-t) / (t_next - t);
      if (crossings++ == 0) first = at;
      else return at - first;
    }
    t = t_next;
    time += dt;
  }
  return std::nan("");
}

// The block's exact period (its inertia about x: m (hy^2 + hz^2) / 3).
inline double blockPeriod(double t0) {
  const double h = kBlockHalf.z(), r = kCurveRadius, i = (kBlockHalf.y() * kBlockHalf.y() + h * h) / 3.0;
  return rollingPeriod([&](double t) { return i + h * h + r * r * t * t; }, [&](double t) { return 2.0 * r * r * t; },
                       [&](double t) { return kG * (r * t * std::cos(t) - h * std::sin(t)); }, t0);
}

// A rod of radius a rolling inside a pipe of radius R: its axis turns about the pipe's by t, the
// rod about its own by (R - a) t / a; I per unit mass about its axis.
inline double rodPeriod(double t0, double inertia_per_mass) {
  const double a = kRodRadius, r = kCurveRadius, spin = (r - a) / a;
  const double j = (r - a) * (r - a) + inertia_per_mass * spin * spin;
  return rollingPeriod([&](double) { return j; }, [](double) { return 0.0; },
                       [&](double t) { return kG * (r - a) * std::sin(t); }, t0);
}

struct Swing {
  double period_s = 0.0;     // mean over the swings read
  int swings = 0;            // full periods read
  double amplitude_kept = 0.0;  // the last swing's amplitude over the first's
  double us_per_step = 0.0;
};

struct RockingScene {
  mesh::GeneratedMesh curve;
  PhysicsWorld world;
  btRigidBody* body = nullptr;
  Rocker rocker;
  double dt;

  // The cylinder (`segments` around) laid along x; a block on its top rolled by t0 from the top
  // line, or a rod inside it rolled by t0 up from its floor.
  RockingScene(Rocker kind, Contact contact, int segments, double t0, int grid_intervals = 16, double step_s = kDt)
      : curve(mesh::cylinder(kCurveRadius, kLength, segments, 4, kCurveRadius, kind != Rocker::Block)), rocker(kind),
        dt(step_s) {
    MeshContactOptions options;
    options.smooth_chart = contact == Contact::SmoothChart;
    options.chart_grid_intervals = grid_intervals;
    // The tube's axis (its z) along x, through (0, 0, 0) for the pipe, (0, 0, -R) for the block's cylinder.
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(0.5 * kPi, Eigen::Vector3d::UnitY()).toRotationMatrix();
    pose.translation() = Eigen::Vector3d(-0.5 * kLength, 0.0, kind == Rocker::Block ? -kCurveRadius : 0.0);
    world.addTexturedMesh(curve.mesh, pose, {kFriction, 0.0, 0.0}, options);
    const double r = kCurveRadius;
    Eigen::Isometry3d at = Eigen::Isometry3d::Identity();
    if (kind == Rocker::Block) {
      // Rolled without slipping: the contact at angle t0 on the cylinder, the underside's middle R t0 behind it.
      const Eigen::Vector3d p(0.0, r * std::sin(t0), r * std::cos(t0) - r), n(0.0, std::sin(t0), std::cos(t0)),
          t(0.0, std::cos(t0), -std::sin(t0));
      at.linear() = Eigen::AngleAxisd(-t0, Eigen::Vector3d::UnitX()).toRotationMatrix();
      at.translation() = p - r * t0 * t + (kBlockHalf.z() + 1e-6) * n;
      body = &world.addBox(kBlockHalf, kBlockMass, at, {kFriction, 0.0, 0.0});
    } else {
      // The rod's axis along x, R - a from the pipe's, t0 up its side.
      at.linear() = Eigen::AngleAxisd(0.5 * kPi, Eigen::Vector3d::UnitY()).toRotationMatrix();
      at.translation() = (r - kRodRadius - 1e-6) * Eigen::Vector3d(0.0, std::sin(t0), -std::cos(t0));
      body = kind == Rocker::Capsule ? &world.addCapsule(kRodRadius, kRodHalfLength, kRodMass, at, {kFriction, 0.0, 0.0})
                                     : &world.addCylinder(kRodRadius, kRodHalfLength, kRodMass, at, {kFriction, 0.0, 0.0});
    }
    body->setActivationState(DISABLE_DEACTIVATION);
  }

  // The swing's angle: the block's roll about x, or the rod's axis's angle about the pipe's.
  double angle() const {
    if (rocker == Rocker::Block) {
      const Eigen::Vector3d up = toEigen(body->getWorldTransform().getBasis().getColumn(2));
      return std::atan2(up.y(), up.z());
    }
    const Eigen::Vector3d c = toEigen(body->getWorldTransform().getOrigin());
    return std::atan2(c.y(), -c.z());
  }

  // The rod's moment about its own axis per unit mass, as Bullet's solver has it.
  double rodInertiaPerMass() const {
    // The rod's axis is its local z (btCapsuleShapeZ, btCylinderShapeZ).
    return 1.0 / (double(body->getInvInertiaDiagLocal().z()) * kRodMass);
  }

  // Steps `seconds` and reads the period from the angle's upward zero crossings.
  Swing run(double seconds) {
    Swing s;
    std::vector<double> crossings;
    double last = angle(), first_peak = 0.0, last_peak = 0.0, peak = 0.0;
    int half_swings = 0;
    const auto start = std::chrono::steady_clock::now();
    const int steps = int(std::lround(seconds / dt));
    for (int k = 1; k <= steps; ++k) {
      world.step(dt);
      const double now = angle();
      peak = std::max(peak, std::fabs(now));
      if ((last < 0.0) != (now < 0.0)) {
        if (half_swings == 0) first_peak = peak;
        last_peak = peak, peak = 0.0, ++half_swings;
      }
      if (last < 0.0 && now >= 0.0) crossings.push_back(dt * (k - 1 + (-last) / (now - last)));
      last = now;
    }
    s.us_per_step = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() / steps;
    s.swings = int(crossings.size()) - 1;
    if (s.swings > 0) s.period_s = (crossings.back() - crossings.front()) / s.swings;
    s.amplitude_kept = first_peak > 0.0 ? last_peak / first_peak : 0.0;
    return s;
  }
};

}  // namespace thx::phys::test::rocking_on_curve
