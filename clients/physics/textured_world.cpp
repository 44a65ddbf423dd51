#include "clients/physics/textured_world.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionShapes/btCollisionShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <algorithm>
#include <utility>

#include "clients/physics/bullet_convert.hpp"
#include "clients/physics/friction_direction.hpp"
#include "clients/physics/relief_collision.hpp"

namespace thx::phys {

void TexturedWorld::addNormalMapPlane(const btCollisionObject* plane, const tex::TexturedSurface* surface,
                                      const NormalMapOptions& options) {
  removeNormalMapPlane(plane);
  planes_.push_back({plane, surface, options});
}

void TexturedWorld::removeNormalMapPlane(const btCollisionObject* plane) {
  std::erase_if(planes_, [&](const NormalMapPlane& p) { return p.body == plane; });
}

void TexturedWorld::addTexturedMesh(const btCollisionObject* body, const mesh::TexturedMesh* mesh,
                                    const MeshContactOptions& options) {
  std::erase_if(meshes_, [&](const TexturedMeshBody& m) { return m.body == body; });
  meshes_.push_back({body, ContactMesh(*mesh), options});
}

void TexturedWorld::addLeaningRelief(const btCollisionObject* relief, const Eigen::Vector3d& lean_local,
                                     const NormalMapOptions& options) {
  std::erase_if(leaning_reliefs_, [&](const LeaningRelief& r) { return r.body == relief; });
  leaning_reliefs_.push_back({relief, lean_local, options});
}

void TexturedWorld::performDiscreteCollisionDetection() {
  crease_sides_.clear();
  if (!meshes_.empty()) {
    btDispatcher* dispatcher = getDispatcher();
    for (int m = 0; m < dispatcher->getNumManifolds(); ++m) {
      const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
      CreaseSides sides = creaseSidesOf(*manifold);
      if (sides.has[0] || sides.has[1]) crease_sides_.emplace_back(manifold, sides);
    }
  }
  btDiscreteDynamicsWorld::performDiscreteCollisionDetection();
  rewritten_ = 0;
  rewriteNormalMapContacts();
  rewriteLeaningReliefContacts();
  rewriteMeshContacts();
  if ((getSolverInfo().m_solverMode & SOLVER_ENABLE_FRICTION_DIRECTION_CACHING) == 0) return;
  btDispatcher* dispatcher = getDispatcher();
  for (int m = 0; m < dispatcher->getNumManifolds(); ++m)
    alignFrictionWithSlip(*dispatcher->getManifoldByIndexInternal(m), double(getDispatchInfo().m_timeStep));
}

StepContext TexturedWorld::stepContext() { return stepContextOf(getSolverInfo(), double(getDispatchInfo().m_timeStep)); }

namespace {

// Calls rewrite(manifold, surface_is_b, surface_to_world, surface, other) for every manifold that
// touches one of `surfaces` (each manifold is rewritten by the first surface in it); returns the
// number of points after.
template <class Surfaces, class Rewrite>
long long rewriteManifoldsWith(btDispatcher& dispatcher, const Surfaces& surfaces, Rewrite rewrite) {
  long long rewritten = 0;
  for (int m = 0; m < dispatcher.getNumManifolds(); ++m) {
    btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(m);
    for (const auto& surface : surfaces) {
      // The manifold's A/B order is fixed by the algorithm that made it, not by insertion order.
      const bool surface_is_b = manifold->getBody1() == surface.body;
      if (!surface_is_b && manifold->getBody0() != surface.body) continue;
      const btCollisionObject* other = surface_is_b ? manifold->getBody0() : manifold->getBody1();
      rewrite(*manifold, surface_is_b, toEigen(surface.body->getWorldTransform()), surface, *other);
      rewritten += manifold->getNumContacts();
      break;
    }
  }
  return rewritten;
}

// The same, calling rewrite(point, surface_is_b, surface_to_world, surface, other) for every point.
template <class Surfaces, class Rewrite>
long long rewriteContactsWith(btDispatcher& dispatcher, const Surfaces& surfaces, Rewrite rewrite) {
  return rewriteManifoldsWith(dispatcher, surfaces,
                              [&](btPersistentManifold& manifold, bool surface_is_b, const Eigen::Isometry3d& surface_to_world,
                                  const auto& surface, const btCollisionObject& other) {
                                for (int k = 0; k < manifold.getNumContacts(); ++k)
                                  rewrite(manifold.getContactPoint(k), surface_is_b, surface_to_world, surface, other);
                              });
}

}  // namespace

void TexturedWorld::rewriteMeshContacts() {
  if (meshes_.empty()) return;
  const StepContext step = stepContext();
  rewritten_ += rewriteManifoldsWith(
      *getDispatcher(), meshes_,
      [&](btPersistentManifold& manifold, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
          const TexturedMeshBody& mesh, const btCollisionObject& other) {
        const btCollisionShape& shape = *other.getCollisionShape();
        // Points made on a chart (relief_collision.hpp) are the surface's already; on a smooth
        // chart a normal map still steers them, and on a normal map's relief its mean slope leans them.
        if (reliefTakesMeshPair(shape, *mesh.body->getCollisionShape())) {
          const bool relief = meshReliefOf(*mesh.body->getCollisionShape())->map != nullptr;
          for (int k = 0; k < manifold.getNumContacts(); ++k) {
            btManifoldPoint& point = manifold.getContactPoint(k);
            if (!relief)
              steerChartContact(point, mesh_is_b, mesh_to_world, mesh.mesh, other, mesh.options, step);
            else
              leanChartContact(point, mesh_is_b, mesh_to_world, mesh.mesh, other, mesh.options, step);
          }
          return;
        }
        // A ball: its manifold as a whole (one point per side where its lift has a crease).
        if (shape.getShapeType() == SPHERE_SHAPE_PROXYTYPE) {
          const ObjectBall ball{toEigen(other.getWorldTransform().getOrigin()),
                                double(static_cast<const btSphereShape&>(shape).getRadius())};
          const CreaseSides* before = nullptr;
          for (const auto& [kept, sides] : crease_sides_)
            if (kept == &manifold) before = &sides;
          applyBallMeshManifold(manifold, mesh_is_b, mesh_to_world, mesh.mesh, ball, other, mesh.options, step, before);
          return;
        }
        for (int k = 0; k < manifold.getNumContacts(); ++k)
          applyMeshContact(manifold.getContactPoint(k), mesh_is_b, mesh_to_world, mesh.mesh, other, mesh.options, step);
      });
}

void TexturedWorld::rewriteNormalMapContacts() {
  if (planes_.empty()) return;
  const StepContext step = stepContext();
  rewritten_ += rewriteContactsWith(*getDispatcher(), planes_,
                                    [&](btManifoldPoint& point, bool plane_is_b, const Eigen::Isometry3d& plane_to_world,
                                        const NormalMapPlane& plane, const btCollisionObject& other) {
                                      applyNormalMap(point, plane_is_b, plane_to_world, *plane.surface, other, plane.options, step);
                                    });
}

void TexturedWorld::rewriteLeaningReliefContacts() {
  if (leaning_reliefs_.empty()) return;
  const StepContext step = stepContext();
  rewritten_ += rewriteContactsWith(*getDispatcher(), leaning_reliefs_,
                                    [&](btManifoldPoint& point, bool relief_is_b, const Eigen::Isometry3d& relief_to_world,
                                        const LeaningRelief& relief, const btCollisionObject& other) {
                                      leanReliefContact(point, relief_is_b, relief_to_world, relief.lean_local, other,
                                                        relief.options, step);
                                    });
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
