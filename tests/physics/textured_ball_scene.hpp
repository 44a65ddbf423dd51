#pragma once
// A ball with a bump map (issue 29; clients/physics/textured_ball.hpp): a 1 cm ball whose faces
// each span one tile (pi r / 2), textured with bumps symmetric under swapping u and v, so the
// texture continues across the faces' edges (meshes/textured_ball_mesh.hpp). Shared by
// tests/physics/test_textured_ball.cpp and benchmarks/bench_textured_ball.cpp.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "clients/physics/bullet_convert.hpp"
#include "clients/physics/textured_ball.hpp"
#include "meshes/textured_ball_mesh.hpp"
#include "tests/physics/physics_fixtures.hpp"

namespace thx::phys::test::textured_ball {

inline constexpr double kRadius = 0.01, kMass = 0.03, kDt = 1e-3;
inline const double kTile = mesh::ballFaceArc(kRadius);  // 15.7 mm
inline constexpr int kBallTexels = 256;                  // 61 µm on the ball

// Rounded bumps, four to a tile each way (3.9 mm apart), their tips `amplitude` above the
// valleys between them: heights at most 0 (the tips touch the smooth ball), symmetric in x and y.
inline double bumps(double x, double y, double amplitude, double period) {
  const double k = 2.0 * kPi / period;
  return -amplitude + amplitude * 0.25 * (1.0 - std::cos(k * x)) * (1.0 - std::cos(k * y));
}
inline tex::TextureMap bumpMap(double amplitude, int texels = kBallTexels) {
  return heightMap(texels, kTile, [amplitude](double x, double y) { return bumps(x, y, amplitude, kTile / 4.0); });
}
// Every texel `depth` deep: the ball is a smooth ball of radius kRadius - depth.
inline tex::TextureMap uniformRecess(double depth, int texels = 64) {
  tex::TextureMap map(texels, texels, tex::Representation::Relief, 2.0 * depth);
  for (int j = 0; j < texels; ++j)
    for (int i = 0; i < texels; ++i) map.setDepth(i, j, depth);
  return map;
}

// The shipped dimpled ball's dimples (scenes/dimpled_ball_grooves.yaml): spherical caps 3.9 mm
// apart (four to a face each way, one at each face's centre), 1.6 mm in rim radius, 0.25 mm deep.
inline const double kDimplePitch = kTile / 4.0;
inline constexpr double kDimpleRim = 0.0016, kDimpleDepth = 0.00025;
inline double dimples(double x, double y) {
  const double cap = (kDimpleRim * kDimpleRim + kDimpleDepth * kDimpleDepth) / (2.0 * kDimpleDepth);
  const double dx = x - std::round(x / kDimplePitch) * kDimplePitch, dy = y - std::round(y / kDimplePitch) * kDimplePitch;
  const double r2 = dx * dx + dy * dy;
  return r2 < kDimpleRim * kDimpleRim ? -(std::sqrt(cap * cap - r2) - (cap - kDimpleDepth)) : 0.0;
}
inline tex::TextureMap dimpleMap() { return heightMap(kBallTexels, kTile, dimples); }

// A turn of the ball drawn from `seed` (std::mt19937, three angles in [-3, 3] rad about x, y and
// z): any orientation, so its lowest point lies anywhere on its cube faces, by their edges and
// corners too.
inline Eigen::Matrix3d anyTurn(unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> angle(-3.0, 3.0);
  return (Eigen::AngleAxisd(angle(random), Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(angle(random), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(angle(random), Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

// A relief dish (docs/physics.md, "Smooth reliefs"): a paraboloid of curvature 10 /m (a sphere's
// of 10 cm radius) as a relief plane's depth, 256 texels over 4 cm (0.16 mm; its depth bends by
// 0.24 um from texel to texel, and by up to 6 of its 0.06 um codes), its centre kDishTop under
// the plane. The dimpled ball is let down in it at dishStart(n): within 1 mm of its centre
// (std::mt19937 seeded 1000 + n), turned by anyTurn(100 + n).
inline constexpr double kDishCurvature = 10.0, kDishExtent = 0.04;
inline constexpr double kDishTop = 0.5 * kDishCurvature * 2.0 * (kDishExtent / 2.0) * (kDishExtent / 2.0);
inline double dishHeight(double x, double y) { return 0.5 * kDishCurvature * (x * x + y * y) - kDishTop; }
inline tex::TextureMap dishMap() { return heightMap(256, kDishExtent, dishHeight); }
inline Eigen::Vector2d dishStart(unsigned n) {
  std::mt19937 random(1000 + n);
  std::uniform_real_distribution<double> within(-0.001, 0.001);
  const double x = within(random), y = within(random);
  return {x, y};
}

inline FaceTexture ballTexture(const tex::TextureMap& map) {
  FaceTexture t;
  t.map = &map;
  t.tile_m = kTile;
  return t;
}

// A ball (kept from turning) pressed by its weight towards the origin along unit `u` for `steps`
// steps of kDt, the world's gravity off: where its centre ends (distance from the origin) and how
// far it strayed from the line at most. Something fixed at the origin holds it.
struct PressedRest {
  double distance_m = 0.0, off_line_m = 0.0;
};
// The lines through the origin a ball is pressed along: on the world's axes and off them.
inline const std::vector<Eigen::Vector3d> kPressLines = {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 1, 0),
                                                         Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(1, -2, 0.5),
                                                         Eigen::Vector3d(-0.3, 0.8, 1)};
inline PressedRest pressTowardsOrigin(PhysicsWorld& world, btRigidBody& ball, const Eigen::Vector3d& u, int steps = 600) {
  world.world().setGravity(btVector3(0, 0, 0));
  ball.setAngularFactor(btVector3(0, 0, 0));
  PressedRest rest;
  for (int k = 0; k < steps; ++k) {
    ball.applyCentralForce(toBt(Eigen::Vector3d(-kMass * kG * u)));
    world.step(kDt);
    const Eigen::Vector3d c = positionOf(ball);
    rest.off_line_m = std::max(rest.off_line_m, (c - c.dot(u) * u).norm());
  }
  rest.distance_m = positionOf(ball).norm();
  return rest;
}

// How far the ball's recessed surface stands above `plane` at its lowest (negative: into it),
// found over the ball's directions rather than the plane's texels: every direction within
// `cone_rad` of straight down, `rings` rings of them, each point's height over the plane's relief
// (sampled where it stands).
inline double lowestGap(const tex::TexturedSurface& plane, const FaceTexture& texture, const Eigen::Isometry3d& pose,
                        double cone_rad = 0.35, int rings = 160) {
  double lowest = 1e9;
  for (int ring = 0; ring <= rings; ++ring) {
    const double polar = cone_rad * double(ring) / double(rings);
    const int around = std::max(1, int(std::ceil(2.0 * kPi * double(ring) * 2.0)));
    for (int k = 0; k < around; ++k) {
      const double azimuth = 2.0 * kPi * double(k) / double(around);
      const Eigen::Vector3d w_world(std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), -std::cos(polar));
      const Eigen::Vector3d w_object = pose.linear().transpose() * w_world;
      const double recess = ballTextureAt(texture, kRadius, w_object).recess_m;
      const Eigen::Vector3d p = pose.translation() + (kRadius - recess) * w_world;
      lowest = std::min(lowest, p.z() - plane.at(p.x(), p.y()).height_m);
    }
  }
  return lowest;
}

// A ball (with `texture`, else plain) set on a flat relief plane (256 texels over 4 cm) at
// `rest_height`, rolling from rest down a virtual slope (gravity tilted by `slope_deg` about y):
// its speed after `seconds`.
inline double rollingSpeed(const FaceTexture* texture, double slope_deg, double seconds, double rest_height,
                           int plane_texels = 256) {
  WorldOptions options;
  options.gravity_m_per_s2 = kG * Eigen::Vector3d(std::sin(deg(slope_deg)), 0.0, -std::cos(deg(slope_deg)));
  PhysicsWorld world(options);
  const SurfaceHolder plane = holdSurface(flatRelief(plane_texels), 0.04, true);
  world.addReliefPlane(plane.surface, {0.5, 0.0, 0.0});
  const Eigen::Isometry3d pose = at(0.0, 0.0, rest_height);
  btRigidBody& ball = texture ? world.addTexturedSphere(kRadius, kMass, pose, {0.5, 0.0, 0.0}, *texture)
                              : world.addSphere(kRadius, kMass, pose, {0.5, 0.0, 0.0});
  for (int k = 0; k < int(std::lround(seconds / kDt)); ++k) world.step(kDt);
  return velocityOf(ball).x();
}

// A bumpy ball (bumpMap(3e-4)) let down onto `plane_map` (a relief over 4 cm), turned so no bump
// tip lies straight down, after `seconds`: how far its surface stands above the plane's relief
// at its lowest (lowestGap), its height, and the fastest it moved over the last 0.5 s.
struct Settled {
  double gap = 0.0, height = 0.0, fastest = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};
inline Settled settleBumpyBall(const tex::TextureMap& plane_map, double seconds) {
  const tex::TextureMap map = bumpMap(3e-4);
  const FaceTexture texture = ballTexture(map);
  PhysicsWorld world;
  const SurfaceHolder plane = holdSurface(plane_map, 0.04, true);
  world.addReliefPlane(plane.surface, {0.5, 0.0, 0.0});
  Eigen::Isometry3d pose = at(0.001, 0.0, kRadius + 2e-4);
  pose.linear() = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()))
                      .toRotationMatrix();
  btRigidBody& ball = world.addTexturedSphere(kRadius, kMass, pose, {0.5, 0.0, 0.0}, texture);
  const int steps = int(std::lround(seconds / kDt));
  Settled s;
  for (int k = 0; k < steps; ++k) {
    world.step(kDt);
    if (k >= steps - 500) s.fastest = std::max(s.fastest, velocityOf(ball).norm());
  }
  const Eigen::Isometry3d rest = toEigen(ball.getWorldTransform());
  s.gap = lowestGap(plane.surface, texture, rest);
  s.centre = rest.translation();
  s.height = s.centre.z();
  return s;
}

// What a ball with `texture` is let down on, its top at z = 0: a plain fixed box 10 x 10 x 2 cm, a
// flat relief plane (256 texels over 4 cm) or a plain plane.
enum class BallGround { PlainBox, FlatRelief, PlainPlane };
struct Rested {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double fastest_late = 0.0;  // over the last 0.5 s
};
// The ball let down at `pose` on `ground`, added before the ball or after it (the pair's two
// orders), after `seconds`.
inline Rested restBallOn(BallGround ground, const FaceTexture& texture, const Eigen::Isometry3d& pose, double seconds,
                         bool ground_first = true) {
  PhysicsWorld world;
  const SurfaceHolder plane = holdSurface(flatRelief(256), 0.04, true);
  const auto add_ground = [&] {
    if (ground == BallGround::FlatRelief) {
      world.addReliefPlane(plane.surface, {1.0, 0.0, 0.0});
    } else if (ground == BallGround::PlainPlane) {
      world.addPlainPlane(at(0.0, 0.0, 0.0), {1.0, 0.0, 0.0});
    } else {
      world.addBox(Eigen::Vector3d(0.05, 0.05, 0.01), 0.0, at(0.0, 0.0, -0.01), {1.0, 0.0, 0.0});
    }
  };
  if (ground_first) add_ground();
  btRigidBody& ball = world.addTexturedSphere(kRadius, kMass, pose, {0.5, 0.0, 0.0}, texture);
  if (!ground_first) add_ground();
  Rested r;
  const int steps = int(std::lround(seconds / kDt));
  for (int k = 0; k < steps; ++k) {
    world.step(kDt);
    if (k >= steps - 500) r.fastest_late = std::max(r.fastest_late, velocityOf(ball).norm());
  }
  r.centre = positionOf(ball);
  return r;
}

// The ball with bumps 0.3 mm high (bumpMap(3e-4)) let down 0.2 mm over `ground`, turned so that
// no bump tip lies straight down, after `seconds`.
inline Rested restBumpyBallOn(BallGround ground, double seconds) {
  const tex::TextureMap bumps = bumpMap(3e-4);
  Eigen::Isometry3d pose = at(0.001, 0.0, kRadius + 2e-4);
  pose.linear() = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()))
                      .toRotationMatrix();
  return restBallOn(ground, ballTexture(bumps), pose, seconds);
}

// Bumps on the plane, 2 mm apart and 0.4 mm high, `texels` over 4 cm.
inline tex::TextureMap bumpyPlane(int texels) {
  return heightMap(texels, 0.04, [](double x, double y) { return bumps(x, y, 4e-4, 0.002); });
}

}  // namespace thx::phys::test::textured_ball
