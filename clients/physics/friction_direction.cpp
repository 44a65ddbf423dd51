#include "clients/physics/friction_direction.hpp"

#include <BulletDynamics/Dynamics/btRigidBody.h>

namespace thx::phys {

namespace {

// A body's velocity at a world point as Bullet's solver sees it before solving: its velocities
// plus the step's external force and torque impulses (btSolverBody::getVelocityInLocalPointNoDelta).
btVector3 velocityAt(const btCollisionObject& object, const btVector3& point, btScalar dt) {
  const btRigidBody* body = btRigidBody::upcast(&object);
  if (body == nullptr) return btVector3(0, 0, 0);
  btVector3 v = body->getLinearVelocity();
  btVector3 w = body->getAngularVelocity();
  if (body->getInvMass() > btScalar(0)) {
    v += body->getTotalForce() * body->getInvMass() * dt;
    w += body->getInvInertiaTensorWorld() * body->getTotalTorque() * dt;
  }
  return v + w.cross(point - object.getWorldTransform().getOrigin());
}

}  // namespace

void alignFrictionWithSlip(btPersistentManifold& manifold, double dt_s) {
  const auto dt = static_cast<btScalar>(dt_s);
  for (int k = 0; k < manifold.getNumContacts(); ++k) {
    btManifoldPoint& p = manifold.getContactPoint(k);
    const btVector3 v = velocityAt(*manifold.getBody0(), p.getPositionWorldOnA(), dt) -
                        velocityAt(*manifold.getBody1(), p.getPositionWorldOnB(), dt);
    const btVector3& n = p.m_normalWorldOnB;
    const btVector3 slip = v - n * n.dot(v);
    if (double(slip.length()) > kMinSlip_m_per_s) {
      p.m_lateralFrictionDir1 = slip.normalized();
      p.m_lateralFrictionDir2 = p.m_lateralFrictionDir1.cross(n);
    } else {
      btPlaneSpace1(n, p.m_lateralFrictionDir1, p.m_lateralFrictionDir2);
    }
    p.m_contactPointFlags |= BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED;
  }
}

}  // namespace thx::phys
