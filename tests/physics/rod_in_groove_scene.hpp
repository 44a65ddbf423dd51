#pragma once
// A rod in a V-groove (issue 29, untextured objects on a relief-textured mesh; relief_collision.hpp):
// a capsule or cylinder (3 mm radius, 2 cm long, 20 g, friction 0.3) lying along one of
// grooved_block_scene.hpp's grooves (4 mm apart, 1 mm deep, walls at theta = 26.57 degrees), or a
// cylinder standing on its end face, on the relief plane, a flat relief mesh, a pipe's grooved
// inside (grooves along its axis) or the top face of a fixed box (0.2 x 0.2 x 0.02 m) whose faces
// carry the relief (box_ground.hpp). The analytic answers: lying, its axis rests r / cos(theta) - D
// above the ridges (its circle touching both walls), and a horizontal force at its centre rolls it
// out over the far wall only above tan(theta) = 0.5 of its weight. A plain ball of the rods' radius
// has the same answers (its cross-section is theirs). Shared by
// tests/physics/test_plain_objects_on_relief_mesh.cpp, test_cylinder_on_box_faces.cpp,
// test_ball_in_v_groove.cpp and benchmarks/bench_rod_in_groove.cpp.
#include <cmath>
#include <memory>

#include "tests/physics/grooved_block_scene.hpp"

namespace thx::phys::test::rod_in_groove {

using namespace grooved_block;

enum class Ground { Plane, FlatMesh, Trough, Box };
// Ball: a plain ball of the rods' radius and mass (their cross-section), on the relief meshes met
// as physics-client meets them (lifted onto the relief as its sphere meets it).
enum class Rod { Capsule, LyingCylinder, StandingCylinder, Ball };

inline constexpr double kRadius = 0.003, kHalfLength = 0.01, kRodMass = 0.02;
inline const double kWall = std::atan(2 * kDepth / kPeriod);

// The axis's height above the ridges' level where a rod of radius r touches both walls.
inline double inTheGroove(double r) { return r / std::cos(kWall) - kDepth; }

struct RodScene {
  SurfaceHolder plane;
  mesh::GeneratedMesh surface;
  tex::TextureMap map;
  tex::BallOnRelief ball_relief;
  std::unique_ptr<PhysicsWorld> world;
  btRigidBody* rod = nullptr;
  Eigen::Vector3d rest = Eigen::Vector3d::Zero();

  // A rod along y over a groove's floor (x = P / 2, or `x_offset_m` from it), a little above where
  // it fits, settled 0.5 s; the grooves' relief `texels` on a side over 4 cm. A ball may be given
  // another radius (wider than 2.24 mm / sin(theta) = 5 mm it rests on the rims, not the walls).
  RodScene(Ground ground, Rod kind, int texels = 128, double ball_radius_m = kRadius, double x_offset_m = 0.0)
      : plane(holdSurface(heightMap(texels, kExtent, vGrooves), kExtent, true)),
        surface(groovedGround(ground == Ground::Trough)),
        map(heightMap(texels, kExtent, vGrooves)),
        ball_relief(map, tex::Address::Wrap),
        world(std::make_unique<PhysicsWorld>()) {
    double y = 0.0;
    if (ground == Ground::Plane) {
      world->addReliefPlane(plane.surface, {1.0, 0.0, 0.0});
    } else if (ground == Ground::Box) {
      FaceTexture faces;
      faces.map = &map;
      faces.tile_m = kExtent;
      world->addTexturedBox(kSlabHalf, 0.0, at(0.0, 0.0, -kSlabHalf.z()), {1.0, 0.0, 0.0}, faces);
    } else {
      y = addGroovedGround(*world, surface, ground == Ground::Trough, map, &ball_relief).y();
    }
    const bool standing = kind == Rod::StandingCylinder;
    const double radius = kind == Rod::Ball ? ball_radius_m : kRadius;
    Eigen::Isometry3d start = at(0.5 * kPeriod + x_offset_m, y, (standing ? kHalfLength : inTheGroove(radius)) + 2e-4);
    if (!standing) start.linear() = Eigen::AngleAxisd(0.5 * kPi, Eigen::Vector3d::UnitX()).toRotationMatrix();
    const BodyMaterial material{kFriction, 0.0, 0.0};
    if (kind == Rod::Ball)
      rod = &world->addSphere(radius, kRodMass, start, material);
    else if (kind == Rod::Capsule)
      rod = &world->addCapsule(kRadius, kHalfLength, kRodMass, start, material);
    else
      rod = &world->addCylinder(standing ? 0.005 : kRadius, kHalfLength, kRodMass, start, material);
    for (int k = 0; k < 500; ++k) world->step(kDt);
    rest = positionOf(*rod);
  }

  // Pushed across the grooves (+x) by a force at its centre for `seconds`: how far it moved.
  Eigen::Vector3d push(double force_over_weight, double seconds = 0.3) {
    for (int k = 0; k < int(std::lround(seconds / kDt)); ++k) {
      rod->activate(true);
      rod->applyCentralForce(btVector3(btScalar(force_over_weight * kRodMass * kG), 0, 0));
      world->step(kDt);
    }
    return positionOf(*rod) - rest;
  }
};

}  // namespace thx::phys::test::rod_in_groove
