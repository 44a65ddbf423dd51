#pragma once
// A grooved block on a grooved plane (issue 29, two textured bodies; clients/physics/textured_box.hpp):
// V-grooves along y, 4 mm apart and 1 mm deep (walls at atan(2 D / P) = 26.6°), on a relief plane
// and on the faces of a 2 x 2 x 1 cm, 50 g block (friction 0.3) set half a period over, so its
// ridges sit in the plane's grooves (or in the same grooves laid on a flat slab mesh's top); or a
// plain block of the same size. Shared by
// tests/physics/test_textured_box.cpp and benchmarks/bench_textured_pair.cpp.
#include <cmath>
#include <memory>

#include "clients/physics/bullet_convert.hpp"
#include "clients/physics/textured_box.hpp"
#include "meshes/mesh_generators.hpp"
#include "textures/ball_on_relief.hpp"
#include "tests/physics/physics_fixtures.hpp"

namespace thx::phys::test::grooved_block {

inline constexpr double kPeriod = 0.004, kDepth = 0.001;  // walls at atan(2 D / P) = 26.6°
inline constexpr double kExtent = 0.04, kMass = 0.05, kDt = 1e-3;
inline const Eigen::Vector3d kHalf(0.01, 0.01, 0.005);

// V-grooves along y: ridges at x = k P, floors half way between.
inline double vGrooves(double x, double) { return -kDepth * 2.0 * std::fabs(x / kPeriod - std::round(x / kPeriod)); }

inline constexpr double kFriction = 0.3;
// The force that starts the block sliding, over its weight: along the grooves (or a plain block
// either way) friction alone; across them, up a wall with friction: tan(wall + atan(mu)).
inline double alongForce() { return kFriction; }
inline double acrossForce() { return std::tan(std::atan(2 * kDepth / kPeriod) + std::atan(kFriction)); }

// The block pushed by a force (over its weight) for `seconds`, after `ramp_seconds` in which the
// force grows from zero: how far its centre moved.
inline Eigen::Vector3d pushBlock(PhysicsWorld& world, btRigidBody& block, const Eigen::Vector3d& force_over_weight,
                                 double seconds, double ramp_seconds = 0.0) {
  const Eigen::Vector3d start = positionOf(block);
  const int ramp = int(std::lround(ramp_seconds / kDt));
  for (int k = 0; k < ramp + int(std::lround(seconds / kDt)); ++k) {
    const double scale = k < ramp ? double(k + 1) / double(ramp) : 1.0;
    block.activate(true);  // a force raised from zero must not let the rest detector put it to sleep
    block.applyCentralForce(toBt(Eigen::Vector3d(scale * force_over_weight * kMass * kG)));
    world.step(kDt);
  }
  return positionOf(block) - start;
}

// The same grooves on a curved mesh (tests/physics/test_textured_box_on_mesh.cpp,
// test_plain_objects_on_relief_mesh.cpp): the inside of a pipe along y, 16 whole tiles round so
// the grooves keep their 4 mm period, its lowest line (a ridge, u = 12 tiles) at z = 0 and
// y = kTroughLength / 2; or the top face of a flat slab at z = 0. Each laid with the grooves'
// relief (`map`, which must outlive the world) at one tile per 4 cm.
inline constexpr double kTroughRadius = 16 * kExtent / (2 * kPi), kTroughLength = 0.1;
inline mesh::GeneratedMesh groovedGround(bool trough) {
  return trough ? mesh::cylinder(kTroughRadius, kTroughLength, 256, 8, kExtent, true)
                : mesh::box({0.2, 0.2, 0.02}, 0.02, kExtent);
}
// Adds `ground` (groovedGround(trough)) to the world; returns the lowest point of its middle.
// `ball_relief` (of `map`; it must outlive the world): how balls meet it, as physics-client gives
// a mesh; nullptr: balls meet it at one point (boxes and rods meet its chart either way).
inline Eigen::Vector3d addGroovedGround(PhysicsWorld& world, const mesh::GeneratedMesh& ground, bool trough,
                                        const tex::TextureMap& map, const tex::BallOnRelief* ball_relief = nullptr) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Eigen::Vector3d bottom = Eigen::Vector3d::Zero();
  if (trough) {
    // The pipe's axis (z) turned onto y, its centre line raised by its radius.
    pose.linear() = Eigen::AngleAxisd(-0.5 * kPi, Eigen::Vector3d::UnitX()).toRotationMatrix();
    pose.translation() = Eigen::Vector3d(0.0, 0.0, kTroughRadius);
    bottom = Eigen::Vector3d(0.0, 0.5 * kTroughLength, 0.0);
  } else {
    pose.translation() = Eigen::Vector3d(0.0, 0.0, -0.01);
  }
  MeshContactOptions options;
  options.texture = &map;
  options.normals_made_for_m = Eigen::Vector2d::Constant(kExtent);
  options.ball_relief = ball_relief;
  world.addTexturedMesh(ground.mesh, pose, {1.0, 0.0, 0.0}, options);
  return bottom;
}

// What the block stands on: the relief plane, or the grooves laid on a flat slab mesh's top
// (groovedGround(false): met on the mesh's relief chart, mesh_relief_chart.hpp), or on the faces
// of a textured box of the slab's size (box_ground.hpp): fixed, fixed and turned over (its -z face
// up, where the face's frame is mirrored), or a 1 kg body resting on a plain plane; or a plain
// fixed box of that size.
enum class BlockGround { Plane, SlabMesh, FixedBox, TurnedBox, MovingBox, PlainBox, PlainPlane };
inline const Eigen::Vector3d kSlabHalf(0.1, 0.1, 0.01);
inline constexpr double kSlabMass = 1.0;

struct Scene {
  SurfaceHolder plane;
  tex::TextureMap block_map;
  std::unique_ptr<mesh::GeneratedMesh> slab;  // with BlockGround::SlabMesh
  std::unique_ptr<PhysicsWorld> world;
  btRigidBody* block = nullptr;
  btRigidBody* slab_box = nullptr;  // with BlockGround::FixedBox or MovingBox

  // The block's ridges over the plane's floors (x = P/2), a little above where they fit; both
  // textures `texels` on a side over 4 cm. block_first: the block is added to the world first, so
  // Bullet hands the pair to the relief algorithm in the other order.
  Scene(bool textured, bool block_first, int texels = 128, const WorldOptions& options = {}, BlockGround ground = BlockGround::Plane)
      : plane(holdSurface(heightMap(texels, kExtent, vGrooves), kExtent, true)),
        block_map(heightMap(texels, kExtent, vGrooves)),
        world(std::make_unique<PhysicsWorld>(options)) {
    const BodyMaterial plane_material{1.0, 0.0, 0.0};  // Bullet multiplies frictions: the block's decides
    const BodyMaterial block_material{kFriction, 0.0, 0.0};
    const Eigen::Isometry3d pose = at(0.5 * kPeriod, 0.0, kHalf.z() - (textured ? kDepth : 0.0) + 2e-4);
    FaceTexture faces;
    faces.map = &block_map;
    faces.tile_m = kExtent;
    auto add_block = [&] {
      block = textured ? &world->addTexturedBox(kHalf, kMass, pose, block_material, faces)
                       : &world->addBox(kHalf, kMass, pose, block_material);
    };
    if (block_first) add_block();
    if (ground == BlockGround::SlabMesh) {
      slab = std::make_unique<mesh::GeneratedMesh>(groovedGround(false));
      addGroovedGround(*world, *slab, false, plane.surface.map());
    } else if (ground == BlockGround::PlainBox) {
      slab_box = &world->addBox(kSlabHalf, 0.0, at(0.0, 0.0, -kSlabHalf.z()), plane_material);
    } else if (ground == BlockGround::PlainPlane) {
      world->addPlainPlane(at(0.0, 0.0, 0.0), plane_material);
    } else if (ground == BlockGround::FixedBox || ground == BlockGround::TurnedBox || ground == BlockGround::MovingBox) {
      // Its top face at z = 0, the grooves' ridges at x = k P as on the plane (u = x / tile; turned
      // over about x, the -z face's u still runs along x).
      FaceTexture slab_faces;
      slab_faces.map = &plane.surface.map();
      slab_faces.tile_m = kExtent;
      const bool moving = ground == BlockGround::MovingBox;
      if (moving) world->addPlainPlane(at(0.0, 0.0, -2.0 * kSlabHalf.z()), plane_material);
      Eigen::Isometry3d slab_pose = at(0.0, 0.0, -kSlabHalf.z());
      if (ground == BlockGround::TurnedBox) slab_pose.linear() = Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()).toRotationMatrix();
      slab_box = &world->addTexturedBox(kSlabHalf, moving ? kSlabMass : 0.0, slab_pose, plane_material, slab_faces);
    } else {
      world->addReliefPlane(plane.surface, plane_material);
    }
    if (!block_first) add_block();
    for (int k = 0; k < 100; ++k) world->step(kDt);  // settle
  }

  // Pushed by a horizontal force for `seconds`: how far the block's centre moved.
  Eigen::Vector3d push(const Eigen::Vector3d& force_over_weight, double seconds, double ramp_seconds = 0.0) {
    return pushBlock(*world, *block, force_over_weight, seconds, ramp_seconds);
  }
};

}  // namespace thx::phys::test::grooved_block
