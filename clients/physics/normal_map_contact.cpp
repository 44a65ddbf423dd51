#include "clients/physics/normal_map_contact.hpp"

#include <BulletCollision/BroadphaseCollision/btBroadphaseProxy.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "clients/physics/bullet_convert.hpp"

namespace thx::phys {

Eigen::Vector3d clampTilt(const Eigen::Vector3d& n, const Eigen::Vector3d& axis, double max_tilt_deg) {
  const double max_tilt = std::clamp(max_tilt_deg, 0.0, 90.0) * std::numbers::pi / 180.0;
  const double along = n.dot(axis);
  if (along >= std::cos(max_tilt)) return n;
  const Eigen::Vector3d lateral = n - along * axis;
  const double length = lateral.norm();
  if (!(length > 0.0)) return axis;
  return std::cos(max_tilt) * axis + lateral * (std::sin(max_tilt) / length);
}

Eigen::Vector3d clampedSampledNormal(const tex::TexturedSurface& surface, double x_local, double y_local,
                                     double max_tilt_deg) {
  return clampTilt(surface.at(x_local, y_local).n_local, Eigen::Vector3d::UnitZ(), max_tilt_deg);
}

StepContext stepContextOf(const btContactSolverInfo& solver, double dt_s) {
  StepContext step;
  step.dt_s = dt_s;
  step.erp = double(solver.m_erp);
  step.split_penetration_threshold = solver.m_splitImpulse ? double(solver.m_splitImpulsePenetrationThreshold) : -1e30;
  return step;
}

namespace {

// Velocity of `body` at world point p (zero for a body that is not a rigid body).
Eigen::Vector3d velocityAt(const btCollisionObject& body, const Eigen::Vector3d& p) {
  const btRigidBody* rb = btRigidBody::upcast(&body);
  if (!rb) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d c = toEigen(rb->getCenterOfMassPosition());
  return toEigen(rb->getLinearVelocity()) + toEigen(rb->getAngularVelocity()).cross(p - c);
}

// The distance that makes Bullet's solver demand v·n >= r (setupContactConstraint: a positive
// distance d allows approach at d / dt, a negative one asks for separation at erp |d| / dt).
double distanceForBias(double r, const StepContext& step) {
  if (r <= 0.0) return -r * step.dt_s;
  // Keep it above the split-impulse threshold: deeper "penetrations" are corrected in position
  // only and would not produce the velocity we ask for.
  return std::max(-r * step.dt_s / step.erp, 0.99 * step.split_penetration_threshold);
}

// steerContact's rule; `ball` null: a point of a shape that is not met as a ball.
void steerOnto(btManifoldPoint& point, bool surface_is_b, const Eigen::Vector3d& n_world,
               const Eigen::Vector3d& n_geometric, const ObjectBall* ball, const btCollisionObject& other,
               bool hold_height, const StepContext& step) {
  // m_normalWorldOnB points from B towards A: the surface's normal if the surface is B, else reversed.
  point.m_normalWorldOnB = toBt(surface_is_b ? n_world : Eigen::Vector3d(-n_world));

  const Eigen::Vector3d on_object = toEigen(surface_is_b ? point.m_positionWorldOnA : point.m_positionWorldOnB);
  // For a ball the solver's normal row sees only the centre's velocity (the lever arm is along
  // n_s); for other shapes the contact point's.
  const Eigen::Vector3d at = ball ? ball->centre_world : on_object;
  Eigen::Vector3d v_ref = velocityAt(other, at);
  if (step.surface_body) v_ref -= velocityAt(*step.surface_body, at);
  if (ball) {
    const btVector3 q = toBt(Eigen::Vector3d(ball->centre_world - ball->radius_m * n_world));
    // The solver takes lever arms from the world positions; the local points are left alone so
    // Bullet's own matching of cached points (by local point on A) keeps working next step.
    point.m_positionWorldOnA = q;
    point.m_positionWorldOnB = q;
  }
  if (hold_height) {
    const double d_g = double(point.m_distance1);  // Bullet's gap along the geometry's own normal
    const double b_g = d_g < 0.0 ? -step.erp * d_g / step.dt_s : -d_g / step.dt_s;
    const Eigen::Vector3d v_t = v_ref - v_ref.dot(n_geometric) * n_geometric;
    const double required = b_g * n_world.dot(n_geometric) + v_t.dot(n_world);
    point.m_distance1 = static_cast<btScalar>(distanceForBias(required, step));
  }
}

}  // namespace

void steerBallContact(btManifoldPoint& point, bool surface_is_b, const Eigen::Vector3d& n_world,
                      const Eigen::Vector3d& n_geometric, const ObjectBall& ball, const btCollisionObject& other,
                      bool hold_height, const StepContext& step) {
  steerOnto(point, surface_is_b, n_world, n_geometric, &ball, other, hold_height, step);
}

void steerContact(btManifoldPoint& point, bool surface_is_b, const Eigen::Vector3d& n_world,
                  const Eigen::Vector3d& n_geometric, const btCollisionObject& other, bool hold_height,
                  const StepContext& step) {
  const btCollisionShape* shape = other.getCollisionShape();
  if (shape->getShapeType() == SPHERE_SHAPE_PROXYTYPE) {
    const ObjectBall ball{toEigen(other.getWorldTransform().getOrigin()),
                          double(static_cast<const btSphereShape*>(shape)->getRadius())};
    steerOnto(point, surface_is_b, n_world, n_geometric, &ball, other, hold_height, step);
  } else {
    steerOnto(point, surface_is_b, n_world, n_geometric, nullptr, other, hold_height, step);
  }
}

void applyNormalMap(btManifoldPoint& point, bool plane_is_b, const Eigen::Isometry3d& plane_to_world,
                    const tex::TexturedSurface& surface, const btCollisionObject& other,
                    const NormalMapOptions& options, const StepContext& step) {
  // Sample where the contact lies on the plane (the plane-side point).
  const btVector3& on_plane = plane_is_b ? point.m_positionWorldOnB : point.m_positionWorldOnA;
  const Eigen::Vector3d p_local = plane_to_world.inverse() * toEigen(on_plane);
  const Eigen::Vector3d n_local = clampedSampledNormal(surface, p_local.x(), p_local.y(), options.max_tilt_deg);
  const Eigen::Vector3d n_world = plane_to_world.linear() * n_local;

  steerContact(point, plane_is_b, n_world, plane_to_world.linear().col(2), other, options.hold_height, step);
}

void leanContact(btManifoldPoint& point, bool surface_is_b, const Eigen::Matrix3d& surface_to_world,
                 const Eigen::Vector3d& up, const Eigen::Vector3d& lean, const btCollisionObject& other,
                 double max_tilt_deg, bool hold_height, const StepContext& step) {
  // The point's own normal (the relief's, towards the object) is the geometry held. A point kept
  // from the last step (a textured box's, a cylinder's on its end face) was leaned then: its own
  // normal is that one unleaned (n = N - grad h scaled, so the lean's inverse is n + (n . N) lean,
  // up to the clamp).
  Eigen::Vector3d n_own = surface_to_world.transpose() * toEigen(point.m_normalWorldOnB) * (surface_is_b ? 1.0 : -1.0);
  if (point.m_contactPointFlags & kLeanedContactFlag) n_own = (n_own + n_own.dot(up) * lean).normalized();
  point.m_contactPointFlags |= kLeanedContactFlag;
  const Eigen::Vector3d n = clampTilt((n_own - n_own.dot(up) * lean).normalized(), up, max_tilt_deg);
  steerContact(point, surface_is_b, surface_to_world * n, surface_to_world * n_own, other, hold_height, step);
}

void leanReliefContact(btManifoldPoint& point, bool plane_is_b, const Eigen::Isometry3d& plane_to_world,
                       const Eigen::Vector3d& lean_local, const btCollisionObject& other, const NormalMapOptions& options,
                       const StepContext& step) {
  if (lean_local.isZero()) return;
  leanContact(point, plane_is_b, plane_to_world.linear(), Eigen::Vector3d::UnitZ(), lean_local, other,
              options.max_tilt_deg, options.hold_height, step);
}

}  // namespace thx::phys
