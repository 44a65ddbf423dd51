#pragma once
// A ball rolling across parallel sine ridges of a relief, 4 per 1 cm tile (2.5 mm apart), laid on
// the flat top of a box mesh or on the relief plane, set rolling along +x across them; shared by
// tests/physics/test_relief_mesh_ridges.cpp (which holds the mesh's lifted ball to the
// rolling-impact law of rolling_over_ridges.hpp) and benchmarks/bench_rolling_ridges.cpp (which
// measures every contact model against it, with its cost).
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

#include "clients/physics/bullet_convert.hpp"
#include "meshes/mesh_generators.hpp"
#include "tests/physics/physics_fixtures.hpp"
#include "tests/physics/rolling_over_ridges.hpp"
#include "textures/ball_on_relief.hpp"

namespace thx::phys::test::ridges {

inline constexpr double kRadius = 0.01, kMass = 0.05, kTile = 0.01, kPeriod = kTile / 4.0;
inline constexpr int kTexels = 256;  // a side of the relief, over one tile

inline double amplitudeFor(double slope) { return slope * kPeriod / (2.0 * kPi); }

// Ridges of slope s (at most) as a relief of kTexels a side over one tile.
inline tex::TextureMap sineRidges(double slope) {
  const double a = amplitudeFor(slope);
  return heightMap(kTexels, kTile, [&](double x, double) { return a * std::sin(2.0 * kPi * x / kPeriod); });
}

struct RidgeRun {
  std::vector<double> period_speeds;  // mean speed along x over each period's length travelled
  double lowest_m = 1.0;              // the centre's lowest height above the smooth top, less r
};

// Where the relief lies: on a mesh (the top of a 1 m box, 5 mm cells) under a lifted or a steered
// ball (MeshContactOptions::lift_ball), or as the relief plane (relief_collision.hpp).
enum class Ground { MeshLifted, MeshSteered, ReliefPlane };

// The ball dropped onto the ridges, settled for 0.3 s, then set rolling along +x at v0 (the
// ridges run along y) for `seconds` or until it has crossed 0.9 m.
inline RidgeRun rollAcross(const tex::TextureMap& map, Ground ground, double dt, double v0, double seconds) {
  WorldOptions world_options;
  world_options.rest.enabled = false;
  // What the world's ground reads: built before the world, which must not outlive it.
  std::optional<mesh::GeneratedMesh> box;
  std::optional<tex::BallOnRelief> ball_relief;
  SurfaceHolder plane;
  if (ground == Ground::ReliefPlane) {
    plane = holdSurface(map, kTile, true, tex::Address::Wrap);
  } else {
    box.emplace(mesh::box({1.0, 0.05, 0.02}, 0.005, kTile));
    ball_relief.emplace(map, tex::Address::Wrap);
  }
  PhysicsWorld world(world_options);
  if (ground == Ground::ReliefPlane) {
    world.addReliefPlane(plane.surface, {1.0, 0.0, 0.0});
  } else {
    MeshContactOptions options;
    options.texture = &map;
    options.sampling.address = tex::Address::Wrap;
    options.ball_relief = &*ball_relief;
    options.lift_ball = ground == Ground::MeshLifted;
    options.normals_made_for_m = Eigen::Vector2d::Constant(kTile);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(0.0, 0.0, -0.01);  // the top face at z = 0
    world.addTexturedMesh(box->mesh, pose, {1.0, 0.0, 0.0}, options);
  }
  Eigen::Isometry3d at = Eigen::Isometry3d::Identity();
  at.translation() = Eigen::Vector3d(-0.45, 0.0, kRadius + 2e-4);
  btRigidBody& ball = world.addSphere(kRadius, kMass, at, {1.0, 0.0, 0.0});
  for (int k = 0; k < int(0.3 / dt); ++k) world.step(dt);
  ball.setLinearVelocity(btVector3(btScalar(v0), 0, 0));
  ball.setAngularVelocity(btVector3(0, btScalar(v0 / kRadius), 0));

  RidgeRun run;
  const double x0 = toEigen(ball.getWorldTransform().getOrigin()).x();
  double t = 0.0, x_last = x0, t_mark = 0.0;
  int marks = 0;
  for (int k = 0; k < int(seconds / dt); ++k) {
    world.step(dt);
    t += dt;
    const Eigen::Vector3d c = toEigen(ball.getWorldTransform().getOrigin());
    run.lowest_m = std::min(run.lowest_m, c.z() - kRadius);
    // Each time the centre passes one more period from where it was set rolling.
    const double next = x0 + (marks + 1) * kPeriod;
    if (c.x() >= next && x_last < next) {
      const double t_cross = t - dt * (c.x() - next) / (c.x() - x_last);
      if (marks > 0) run.period_speeds.push_back(kPeriod / (t_cross - t_mark));
      t_mark = t_cross;
      ++marks;
    }
    x_last = c.x();
    if (c.x() > 0.45) break;
  }
  return run;
}

// The ridges as the relief stores them: heights at texel centres (x = (k + 1/2) texel from the
// sine's origin, heightMap's), linear between them along x, as BallOnRelief reads them.
inline std::function<double(double)> storedRidges(double slope) {
  const double a = amplitudeFor(slope), texel = kTile / kTexels;
  return [a, texel](double x) {
    const double k = std::floor(x / texel), w = x / texel - k;
    auto at = [&](double i) { return a * std::sin(2.0 * kPi * (i + 0.5) * texel / kPeriod); };
    return (1.0 - w) * at(k) + w * at(k + 1.0);
  };
}

inline RollingOverRidges referenceFor(double slope) {
  return RollingOverRidges(storedRidges(slope), kPeriod, kRadius, 4096);
}

// The speed kept from the 6th period set rolling to the 66th.
inline constexpr int kFirst = 5, kPeriods = 60;
inline double speedKept(const std::vector<double>& period_speeds) {
  if (period_speeds.size() <= std::size_t(kFirst + kPeriods)) return 0.0;
  return period_speeds[std::size_t(kFirst + kPeriods)] / period_speeds[std::size_t(kFirst)];
}

}  // namespace thx::phys::test::ridges
