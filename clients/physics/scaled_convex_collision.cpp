#include "clients/physics/scaled_convex_collision.hpp"

#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>

#include <optional>

namespace thx::phys {

namespace {

constexpr btScalar kFactor = btScalar(ScaledConvexAlgorithm::kScale);

bool handled(int type) {
  return type == SPHERE_SHAPE_PROXYTYPE || type == BOX_SHAPE_PROXYTYPE || type == CAPSULE_SHAPE_PROXYTYPE ||
         type == CYLINDER_SHAPE_PROXYTYPE;
}

// A copy of one of the handled shapes, kFactor times larger (margin included), on the stack.
class ScaledShape {
 public:
  explicit ScaledShape(const btCollisionShape& shape) {
    switch (shape.getShapeType()) {
      case SPHERE_SHAPE_PROXYTYPE:
        sphere_.emplace(kFactor * static_cast<const btSphereShape&>(shape).getRadius());
        convex_ = &*sphere_;
        break;
      case BOX_SHAPE_PROXYTYPE: {
        const auto& box = static_cast<const btBoxShape&>(shape);
        box_.emplace(kFactor * box.getHalfExtentsWithMargin());
        box_->setMargin(kFactor * box.getMargin());  // keeps the scaled outer extents
        convex_ = &*box_;
        break;
      }
      case CAPSULE_SHAPE_PROXYTYPE: {
        const auto& c = static_cast<const btCapsuleShape&>(shape);
        const btScalar r = kFactor * c.getRadius(), h = 2 * kFactor * c.getHalfHeight();
        convex_ = c.getUpAxis() == 0   ? static_cast<btConvexShape*>(&capsule_x_.emplace(r, h))
                  : c.getUpAxis() == 1 ? static_cast<btConvexShape*>(&capsule_y_.emplace(r, h))
                                       : static_cast<btConvexShape*>(&capsule_z_.emplace(r, h));
        break;
      }
      default: {  // CYLINDER_SHAPE_PROXYTYPE
        const auto& c = static_cast<const btCylinderShape&>(shape);
        const btVector3 half = kFactor * c.getHalfExtentsWithMargin();
        btCylinderShape* cylinder = c.getUpAxis() == 0   ? static_cast<btCylinderShape*>(&cylinder_x_.emplace(half))
                                    : c.getUpAxis() == 1 ? &cylinder_y_.emplace(half)
                                                         : static_cast<btCylinderShape*>(&cylinder_z_.emplace(half));
        cylinder->setMargin(kFactor * c.getMargin());
        convex_ = cylinder;
        break;
      }
    }
  }
  const btConvexShape* get() const { return convex_; }

 private:
  std::optional<btSphereShape> sphere_;
  std::optional<btBoxShape> box_;
  std::optional<btCapsuleShapeX> capsule_x_;
  std::optional<btCapsuleShape> capsule_y_;
  std::optional<btCapsuleShapeZ> capsule_z_;
  std::optional<btCylinderShapeX> cylinder_x_;
  std::optional<btCylinderShape> cylinder_y_;
  std::optional<btCylinderShapeZ> cylinder_z_;
  const btConvexShape* convex_ = nullptr;
};

// GJK's answer in the scaled frame, handed to Bullet's manifold in SI units.
class ScaledBack : public btDiscreteCollisionDetectorInterface::Result {
 public:
  ScaledBack(btManifoldResult& out, const btVector3& origin) : out_(out), origin_(origin) {}
  void setShapeIdentifiersA(int part, int index) override { out_.setShapeIdentifiersA(part, index); }
  void setShapeIdentifiersB(int part, int index) override { out_.setShapeIdentifiersB(part, index); }
  void addContactPoint(const btVector3& normal_on_b, const btVector3& point_on_b, btScalar depth) override {
    out_.addContactPoint(normal_on_b, origin_ + point_on_b / kFactor, depth / kFactor);
  }

 private:
  btManifoldResult& out_;
  btVector3 origin_;
};

}  // namespace

bool usesScaledConvex(int t0, int t1) {
  if (!handled(t0) || !handled(t1)) return false;
  const bool round0 = t0 == SPHERE_SHAPE_PROXYTYPE || t0 == CAPSULE_SHAPE_PROXYTYPE;
  const bool round1 = t1 == SPHERE_SHAPE_PROXYTYPE || t1 == CAPSULE_SHAPE_PROXYTYPE;
  // Bullet's exact ones: box-box and any pair of spheres and capsules.
  return !(round0 && round1) && !(t0 == BOX_SHAPE_PROXYTYPE && t1 == BOX_SHAPE_PROXYTYPE);
}

void ScaledConvexAlgorithm::processCollision(const btCollisionObjectWrapper* body0,
                                             const btCollisionObjectWrapper* body1, const btDispatcherInfo& info,
                                             btManifoldResult* result) {
  btPersistentManifold* manifold = manifoldFor(body0->getCollisionObject(), body1->getCollisionObject());
  result->setPersistentManifold(manifold);

  const ScaledShape a(*body0->getCollisionShape()), b(*body1->getCollisionShape());
  const btTransform& t0 = body0->getWorldTransform();
  const btTransform& t1 = body1->getWorldTransform();
  // Scaled about the pair's midpoint: small coordinates keep the float precision of SI ones.
  const btVector3 origin = btScalar(0.5) * (t0.getOrigin() + t1.getOrigin());
  btGjkPairDetector::ClosestPointInput input;
  input.m_transformA = btTransform(t0.getBasis(), kFactor * (t0.getOrigin() - origin));
  input.m_transformB = btTransform(t1.getBasis(), kFactor * (t1.getOrigin() - origin));
  const btScalar reach = a.get()->getMargin() + b.get()->getMargin() + kFactor * manifold->getContactBreakingThreshold();
  input.m_maximumDistanceSquared = reach * reach;

  btVoronoiSimplexSolver simplex;
  btGjkEpaPenetrationDepthSolver depth_solver;
  btGjkPairDetector gjk(a.get(), b.get(), &simplex, &depth_solver);
  ScaledBack back(*result, origin);
  gjk.getClosestPoints(input, back, info.m_debugDraw);
  if (ownsManifold()) result->refreshContactPoints();
}

void registerScaledConvexCollision(btCollisionDispatcher& dispatcher) {
  static ScaledConvexAlgorithm::CreateFunc create;
  const int types[] = {SPHERE_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE, CAPSULE_SHAPE_PROXYTYPE, CYLINDER_SHAPE_PROXYTYPE};
  for (int t0 : types)
    for (int t1 : types)
      if (usesScaledConvex(t0, t1)) dispatcher.registerCollisionCreateFunc(t0, t1, &create);
}

}  // namespace thx::phys
