#include "clients/physics/textured_world.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionShapes/btCollisionShape.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <algorithm>
#include <utility>

#include "clients/physics/bullet_convert.hpp"
#include "clients/physics/friction_direction.hpp"

namespace thx::phys {

void TexturedWorld::addNormalMapPlane(const btCollisionObject* plane, const tex::TexturedSurface* surface,
                                      const NormalMapOptions& options) {
  removeNormalMapPlane(plane);
  planes_.push_back({plane, surface, options});
}

void TexturedWorld::removeNormalMapPlane(const btCollisionObject* plane) {
  std::erase_if(planes_, [&](const NormalMapPlane& p) { return p.body == plane; });
}

void TexturedWorld::performDiscreteCollisionDetection() {
  btDiscreteDynamicsWorld::performDiscreteCollisionDetection();
  rewritten_ = 0;
  rewriteNormalMapContacts();
  if ((getSolverInfo().m_solverMode & SOLVER_ENABLE_FRICTION_DIRECTION_CACHING) == 0) return;
  btDispatcher* dispatcher = getDispatcher();
  for (int m = 0; m < dispatcher->getNumManifolds(); ++m)
    alignFrictionWithSlip(*dispatcher->getManifoldByIndexInternal(m), double(getDispatchInfo().m_timeStep));
}

void TexturedWorld::rewriteNormalMapContacts() {
  if (planes_.empty()) return;
  StepContext step;
  step.dt_s = double(getDispatchInfo().m_timeStep);
  step.erp = double(getSolverInfo().m_erp);
  step.split_penetration_threshold =
      getSolverInfo().m_splitImpulse ? double(getSolverInfo().m_splitImpulsePenetrationThreshold) : -1e30;
  btDispatcher* dispatcher = getDispatcher();
  const int count = dispatcher->getNumManifolds();
  for (int m = 0; m < count; ++m) {
    btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
    for (const NormalMapPlane& plane : planes_) {
      // The manifold's A/B order is fixed by the algorithm that made it, not by insertion order.
      const bool plane_is_b = manifold->getBody1() == plane.body;
      if (!plane_is_b && manifold->getBody0() != plane.body) continue;
      const btCollisionObject* other = plane_is_b ? manifold->getBody0() : manifold->getBody1();
      const Eigen::Isometry3d plane_to_world = toEigen(plane.body->getWorldTransform());
      for (int k = 0; k < manifold->getNumContacts(); ++k) {
        applyNormalMap(manifold->getContactPoint(k), plane_is_b, plane_to_world, *plane.surface, *other,
                       plane.options, step);
        ++rewritten_;
      }
      break;
    }
  }
}

void TexturedWorld::solveConstraints(btContactSolverInfo& info) {
  if (!rest_.enabled) return btDiscreteDynamicsWorld::solveConstraints(info);
  // Kinematic bodies awake and touching nothing (few: the pen).
  thread_local std::vector<std::pair<btCollisionObject*, int>> quiet;
  quiet.clear();
  for (int i = 0; i < m_collisionObjects.size(); ++i) {
    btCollisionObject* o = m_collisionObjects[i];
    if (o->isKinematicObject() && o->getActivationState() != ISLAND_SLEEPING) quiet.emplace_back(o, o->getActivationState());
  }
  if (!quiet.empty()) {
    btDispatcher* dispatcher = getDispatcher();
    for (int m = 0; m < dispatcher->getNumManifolds(); ++m) {
      const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
      if (manifold->getNumContacts() == 0) continue;
      std::erase_if(quiet, [&](const auto& k) { return k.first == manifold->getBody0() || k.first == manifold->getBody1(); });
    }
  }
  for (const auto& [object, state] : quiet) object->forceActivationState(ISLAND_SLEEPING);
  btDiscreteDynamicsWorld::solveConstraints(info);
  for (const auto& [object, state] : quiet) object->forceActivationState(state);
}

// Bullet's btDiscreteDynamicsWorld::updateActivationState with the rest criterion of
// rest_detector.hpp in place of btRigidBody::updateDeactivation / wantsSleeping.
void TexturedWorld::updateActivationState(btScalar time_step) {
  if (!rest_.enabled) return btDiscreteDynamicsWorld::updateActivationState(time_step);
  for (int i = 0; i < m_nonStaticRigidBodies.size(); ++i) {
    btRigidBody* body = m_nonStaticRigidBodies[i];
    const int state = body->getActivationState();
    if (state == DISABLE_DEACTIVATION || state == DISABLE_SIMULATION || body->isStaticOrKinematicObject()) continue;
    RestDetector& detector = rest_detectors_[body];
    if (state == ISLAND_SLEEPING) {
      body->setLinearVelocity(btVector3(0, 0, 0));
      body->setAngularVelocity(btVector3(0, 0, 0));
      detector.restart();  // when it wakes, its window starts there
      continue;
    }
    btVector3 centre;
    btScalar radius;
    body->getCollisionShape()->getBoundingSphere(centre, radius);
    const bool at_rest = detector.update(body->getWorldTransform(), double(radius), double(time_step), rest_);
    body->setActivationState(at_rest ? WANTS_DEACTIVATION : ACTIVE_TAG);
  }
}

}  // namespace thx::phys
