#include "clients/physics/textured_world.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <algorithm>

#include "clients/physics/bullet_convert.hpp"

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

}  // namespace thx::phys
