#include "clients/physics/box_ground.hpp"

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>

#include <utility>

#include "clients/physics/relief_collision.hpp"
#include "clients/physics/scaled_convex_collision.hpp"
#include "clients/physics/textured_ball.hpp"

namespace thx::phys {

namespace {

bool isBox(const btCollisionShape& s) { return s.getShapeType() == BOX_SHAPE_PROXYTYPE; }

double boxVolume(const btCollisionShape& s) {
  const btVector3 h = static_cast<const btBoxShape&>(s).getHalfExtentsWithMargin();
  return double(h.x()) * double(h.y()) * double(h.z());
}

}  // namespace

PairGround texturedPairGround(const btCollisionShape& first, const btCollisionShape& second) {
  if (!hasObjectTexture(first) && !hasObjectTexture(second)) return PairGround::None;
  // A ball with a bump map (a plain ball meets a textured box's faces by BallOnObjectFacesAlgorithm, below).
  const auto ball = [](const btCollisionShape& s) { return ballTextureOf(s) != nullptr; };
  if (isBox(first) && isBox(second)) return boxVolume(first) > boxVolume(second) ? PairGround::First : PairGround::Second;
  if (isBox(first) && ball(second)) return PairGround::First;
  if (ball(first) && isBox(second)) return PairGround::Second;
  // Two balls with bump maps: the larger under the other (the second on a tie); a cylinder on a
  // ball with a bump map.
  const auto radius = [](const btCollisionShape& s) { return double(static_cast<const btSphereShape&>(s).getRadius()); };
  if (ball(first) && ball(second)) return radius(first) > radius(second) ? PairGround::First : PairGround::Second;
  const auto isCylinder = [](const btCollisionShape& s) { return s.getShapeType() == CYLINDER_SHAPE_PROXYTYPE; };
  if (ball(first) && isCylinder(second)) return PairGround::First;
  if (isCylinder(first) && ball(second)) return PairGround::Second;
  // A textured box under a cylinder (a plain box and a cylinder have no texture between them).
  const auto texturedBox = [](const btCollisionShape& s) { return isBox(s) && hasObjectTexture(s); };
  if (texturedBox(first) && isCylinder(second)) return PairGround::First;
  if (isCylinder(first) && texturedBox(second)) return PairGround::Second;
  return PairGround::None;
}

btCollisionAlgorithm* BoxGroundCreateFunc::CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                                    const btCollisionObjectWrapper* body0,
                                                                    const btCollisionObjectWrapper* body1) {
  switch (texturedPairGround(*body0->getCollisionShape(), *body1->getCollisionShape())) {
    case PairGround::First:  // body0 is the ground: the relief algorithm's "swapped" order
      return ManifoldAlgorithm::create<ReliefCollisionAlgorithm>(ci, body0, body1, true,
                                                                 catalog->ground(*body0->getCollisionShape()));
    case PairGround::Second:
      return ManifoldAlgorithm::create<ReliefCollisionAlgorithm>(ci, body0, body1, false,
                                                                 catalog->ground(*body1->getCollisionShape()));
    case PairGround::None:
      break;
  }
  // A plain ball or a capsule against a textured box or a ball with a bump map: its surface as a
  // relief mesh's.
  const btCollisionShape& s0 = *body0->getCollisionShape();
  const btCollisionShape& s1 = *body1->getCollisionShape();
  if (meetsFacesAsBalls(s1))
    if (const ObjectFaces* faces = catalog->find(s0))
      return ManifoldAlgorithm::create<BallOnObjectFacesAlgorithm>(ci, body0, body1, true, faces, catalog);
  if (meetsFacesAsBalls(s0))
    if (const ObjectFaces* faces = catalog->find(s1))
      return ManifoldAlgorithm::create<BallOnObjectFacesAlgorithm>(ci, body0, body1, false, faces, catalog);
  return otherwise->CreateCollisionAlgorithm(ci, body0, body1);
}

std::unique_ptr<BoxGroundRegistration> registerBoxGroundCollision(btCollisionDispatcher& dispatcher,
                                                                  btCollisionConfiguration& configuration,
                                                                  bool scaled_convex) {
  auto registration = std::make_unique<BoxGroundRegistration>();
  registration->scaled_convex = std::make_unique<ScaledConvexAlgorithm::CreateFunc>();
  const int types[] = {SPHERE_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE, CAPSULE_SHAPE_PROXYTYPE, CYLINDER_SHAPE_PROXYTYPE};
  for (int other : types) {
    for (const bool box_first : {true, false}) {
      if (other == BOX_SHAPE_PROXYTYPE && !box_first) continue;
      const int t0 = box_first ? BOX_SHAPE_PROXYTYPE : other, t1 = box_first ? other : BOX_SHAPE_PROXYTYPE;
      btCollisionAlgorithmCreateFunc* otherwise = scaled_convex && usesScaledConvex(t0, t1)
                                                      ? registration->scaled_convex.get()
                                                      : configuration.getCollisionAlgorithmCreateFunc(t0, t1);
      registration->funcs.push_back(std::make_unique<BoxGroundCreateFunc>(otherwise, &registration->faces));
      dispatcher.registerCollisionCreateFunc(t0, t1, registration->funcs.back().get());
    }
  }
  // A ball with a bump map against a ball, a capsule or a cylinder (the pairs without a box).
  for (const auto& [t0, t1] : {std::pair{SPHERE_SHAPE_PROXYTYPE, SPHERE_SHAPE_PROXYTYPE},
                               std::pair{SPHERE_SHAPE_PROXYTYPE, CAPSULE_SHAPE_PROXYTYPE},
                               std::pair{CAPSULE_SHAPE_PROXYTYPE, SPHERE_SHAPE_PROXYTYPE},
                               std::pair{SPHERE_SHAPE_PROXYTYPE, CYLINDER_SHAPE_PROXYTYPE},
                               std::pair{CYLINDER_SHAPE_PROXYTYPE, SPHERE_SHAPE_PROXYTYPE}}) {
    btCollisionAlgorithmCreateFunc* otherwise = scaled_convex && usesScaledConvex(t0, t1)
                                                    ? registration->scaled_convex.get()
                                                    : configuration.getCollisionAlgorithmCreateFunc(t0, t1);
    registration->funcs.push_back(std::make_unique<BoxGroundCreateFunc>(otherwise, &registration->faces));
    dispatcher.registerCollisionCreateFunc(t0, t1, registration->funcs.back().get());
  }
  return registration;
}

}  // namespace thx::phys
