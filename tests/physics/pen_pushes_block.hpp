#pragma once
// The pen pushing the grooved block of grooved_block_scene.hpp through a side face (issue 29, a
// textured box against another object): shared by tests/physics/test_capsule_on_box_faces.cpp
// (the pen's capsule, met as its balls: ball_on_object_faces.hpp) and
// test_cylinder_on_box_faces.cpp (a cylinder, met by the rod rules on the face's chart).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "tests/physics/grooved_block_scene.hpp"

namespace thx::phys::test::grooved_block {

// The pen (4 mm, upright, frictionless, kinematic: a capsule, or a cylinder as long) pushes the
// grooved block's side face at 20 mm/s while moving 10 mm/s along it, for 0.4 s. On the +x face the grooves run upright
// (u along y): the pen sits in one, feels its walls resist the motion along the face and drags
// the face with it (the block turns); on the +y face they lie level (u along z): the pen slides
// along them as along a plain face. On the coarse box (a plain block) nothing resists it.
struct Pushed {
  double pen_along = 0.0, block_along = 0.0, block_pushed = 0.0, fastest_up = 0.0;
  double pen_on_face = 0.0;  // how far the pen moved along the face in the block's frame
  double turned_deg = 0.0;   // the block's turn about the vertical
  // The force on the pen summed over the steps it touched, in the block's frame: along the face
  // against the pen's motion, over the push out of the face.
  double resisted = 0.0, pushed_back = 0.0;
};
// The impulse `other` gave `body` over the last step (normal rows: the pen is frictionless).
inline Eigen::Vector3d impulseOn(PhysicsWorld& world, const btRigidBody& body, const btRigidBody& other) {
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  btDispatcher* d = world.world().getDispatcher();
  for (int m = 0; m < d->getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = d->getManifoldByIndexInternal(m);
    const bool body_is_a = manifold->getBody0() == &body && manifold->getBody1() == &other;
    if (!body_is_a && !(manifold->getBody1() == &body && manifold->getBody0() == &other)) continue;
    for (int k = 0; k < manifold->getNumContacts(); ++k) {
      const btManifoldPoint& p = manifold->getContactPoint(k);
      total += (body_is_a ? 1.0 : -1.0) * double(p.m_appliedImpulse) * toEigen(p.m_normalWorldOnB);
    }
  }
  return total;
}

inline constexpr double kPushSpeed = 0.02, kAlongSpeed = 0.01;
inline constexpr int kSteps = 400;
enum class PenShape { Capsule, Cylinder };
inline Pushed pushWithPen(bool textured, bool upright_grooves, PenShape shape = PenShape::Capsule) {
  const tex::TextureMap map = heightMap(128, kExtent, vGrooves);
  FaceTexture faces;
  faces.map = &map;
  faces.tile_m = kExtent;
  PhysicsWorld world;
  world.addPlainPlane(at(0.0, 0.0, 0.0), {1.0, 0.0, 0.0});
  const Eigen::Isometry3d block_pose = at(0.0, 0.0, kHalf.z() + 1e-5);
  btRigidBody& block = textured ? world.addTexturedBox(kHalf, kMass, block_pose, {kFriction, 0.0, 0.0}, faces)
                                : world.addBox(kHalf, kMass, block_pose, {kFriction, 0.0, 0.0});
  for (int k = 0; k < 100; ++k) world.step(kDt);  // settled
  // Push along -e_in at the face, move along e_along; the pen a groove's floor over the face's
  // ridge at its centre (u = 0), half a millimetre off the face, its tip 2 mm over the plane.
  const Eigen::Vector3d e_in = upright_grooves ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e_along = upright_grooves ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
  constexpr double kPenRadius = 0.004, kPenHalf = 0.05;
  const Eigen::Vector3d start = e_in * (kHalf.x() + kPenRadius + 5e-4) + e_along * (upright_grooves ? 0.5 * kPeriod : 0.0) +
                                Eigen::Vector3d(0.0, 0.0, kPenRadius + kPenHalf + 0.002);
  btRigidBody& pen = shape == PenShape::Capsule
                         ? world.addCapsule(kPenRadius, kPenHalf, 0.0, at(start.x(), start.y(), start.z()), {0.0, 0.0, 0.0})
                         : world.addCylinder(kPenRadius, kPenHalf + kPenRadius, 0.0, at(start.x(), start.y(), start.z()),
                                             {0.0, 0.0, 0.0});
  pen.setCollisionFlags(pen.getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  pen.setActivationState(DISABLE_DEACTIVATION);
  const Eigen::Vector3d block_start = positionOf(block);
  const auto penOnFace = [&] {
    return Eigen::Vector3d(toEigen(block.getWorldTransform().inverse() * pen.getWorldTransform().getOrigin())).dot(e_along);
  };
  Pushed pushed;
  double touched_on_face = 0.0;
  bool touched = false;
  for (int k = 1; k <= kSteps; ++k) {
    const Eigen::Vector3d p = start - kPushSpeed * k * kDt * e_in + kAlongSpeed * k * kDt * e_along;
    btTransform t = pen.getWorldTransform();
    t.setOrigin(toBt(p));
    pen.setWorldTransform(t);
    world.step(kDt);
    pushed.fastest_up = std::max(pushed.fastest_up, double(block.getLinearVelocity().z()));
    const Eigen::Matrix3d block_axes = toEigen(block.getWorldTransform().getBasis());
    const Eigen::Vector3d on_pen = impulseOn(world, pen, block);
    pushed.resisted -= on_pen.dot(block_axes * e_along);
    pushed.pushed_back += on_pen.dot(block_axes * e_in);
    if (!touched && (positionOf(block) - block_start).norm() > 1e-5) {
      touched = true;
      touched_on_face = penOnFace();
    }
  }
  pushed.pen_on_face = penOnFace() - touched_on_face;
  const Eigen::Matrix3d turn = toEigen(block.getWorldTransform().getBasis());
  pushed.turned_deg = std::atan2(turn(1, 0), turn(0, 0)) * 180.0 / kPi;
  const Eigen::Vector3d moved = positionOf(block) - block_start;
  pushed.pen_along = kAlongSpeed * kSteps * kDt;
  pushed.block_along = moved.dot(e_along);
  pushed.block_pushed = -moved.dot(e_in);
  return pushed;
}

// The four pushes of `shape`'s pen, printed: on upright grooves it stays in its groove (in the
// block's frame) and feels them resist its motion along the face; level ones and a plain face let
// it slide, frictionless; the block is pushed and never thrown up.
inline void expectThePenFeelsUprightGroovesOnly(PenShape shape) {
  const Pushed across = pushWithPen(true, true, shape), along = pushWithPen(true, false, shape);
  const Pushed plain_x = pushWithPen(false, true, shape), plain_y = pushWithPen(false, false, shape);
  for (const auto& [name, p] : {std::pair{"grooves upright (+x face)", across}, std::pair{"grooves level (+y face)", along},
                                std::pair{"plain block, +x face", plain_x}, std::pair{"plain block, +y face", plain_y}})
    std::printf("[measured] %s pen, %s: pushed %.2f mm, dragged %.3f mm of the pen's %.1f mm along the face and turned %.2f deg, "
                "the pen moved %.3f mm along the face from where it touched, its force along the face against its motion %.3f of "
                "the push, fastest up %.4f m/s\n",
                shape == PenShape::Capsule ? "capsule" : "cylinder", name, p.block_pushed * 1e3, p.block_along * 1e3,
                p.pen_along * 1e3, p.turned_deg, p.pen_on_face * 1e3, p.resisted / p.pushed_back, p.fastest_up);
  EXPECT_LT(std::fabs(across.pen_on_face), 0.25 * kPeriod);
  // How hard the walls resist depends on how the block turns on the plane under it: standing on
  // its grooves' ridges (its texture read on the plain plane, since 2026-12-05) it turns more
  // freely than on its coarse box's four corners, and the capsule felt 0.020 of the push instead
  // of 0.123. Still more than a plain face or level grooves give.
  double others = 0.0;
  for (const Pushed& p : {along, plain_x, plain_y}) others = std::max(others, std::fabs(p.resisted) / p.pushed_back);
  EXPECT_GT(across.resisted / across.pushed_back, 2.0 * others);
  for (const Pushed& p : {along, plain_x, plain_y}) {
    EXPECT_GT(p.pen_on_face, 0.25 * p.pen_along);
    EXPECT_LT(std::fabs(p.resisted), 0.02 * p.pushed_back);
  }
  for (const Pushed& p : {across, along, plain_x, plain_y}) {
    EXPECT_GT(p.block_pushed, 0.004);  // the pen's 8 mm less the 0.5 mm gap and whatever its grooves let it in
    EXPECT_LT(p.fastest_up, 0.01);
  }
}

}  // namespace thx::phys::test::grooved_block
