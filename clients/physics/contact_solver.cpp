#include "clients/physics/contact_solver.hpp"

#include <algorithm>
#include <initializer_list>

namespace thx::phys {

btScalar ContactSolver::solveGroup(btCollisionObject** bodies, int num_bodies, btPersistentManifold** manifolds,
                                   int num_manifolds, btTypedConstraint** constraints, int num_constraints,
                                   const btContactSolverInfo& info, btIDebugDraw* debug_draw,
                                   btDispatcher* dispatcher) {
  released_ = 0;
  clamped_ = 0;
  return btSequentialImpulseConstraintSolver::solveGroup(bodies, num_bodies, manifolds, num_manifolds, constraints,
                                                         num_constraints, info, debug_draw, dispatcher);
}

namespace {
// Tangential speed of the contact's two bodies at its point, from their velocities before the
// solve and without this step's external impulses (gravity): how fast the point really slides.
btScalar slidingSpeed(const btSolverBody& a, const btSolverBody& b, const btManifoldPoint& point) {
  const btVector3 rel_a = point.getPositionWorldOnA() - a.getWorldTransform().getOrigin();
  const btVector3 rel_b = point.getPositionWorldOnB() - b.getWorldTransform().getOrigin();
  const btVector3 v = (a.m_linearVelocity + a.m_angularVelocity.cross(rel_a)) - (b.m_linearVelocity + b.m_angularVelocity.cross(rel_b));
  const btVector3& n = point.m_normalWorldOnB;
  return (v - n * n.dot(v)).length();
}
}  // namespace

void ContactSolver::convertContacts(btPersistentManifold** manifolds, int num_manifolds,
                                    const btContactSolverInfo& info) {
  btSequentialImpulseConstraintSolver::convertContacts(manifolds, num_manifolds, info);
  const int contacts = m_tmpSolverContactConstraintPool.size();
  sliding_.resize(std::size_t(contacts));
  for (int k = 0; k < contacts; ++k) {
    const btSolverConstraint& contact = m_tmpSolverContactConstraintPool[k];
    sliding_[std::size_t(k)] = slidingSpeed(m_tmpSolverBodyPool[contact.m_solverBodyIdA], m_tmpSolverBodyPool[contact.m_solverBodyIdB],
                                            *static_cast<const btManifoldPoint*>(contact.m_originalContactPoint)) > kSlidingSpeed;
  }
  for (int k = 0; k < contacts; ++k) {
    const btSolverConstraint& contact = m_tmpSolverContactConstraintPool[k];
    auto& point = *static_cast<btManifoldPoint*>(contact.m_originalContactPoint);
    // Bullet added it itself when the point has rolling friction.
    if (!(point.m_combinedSpinningFriction > btScalar(0)) || point.m_combinedRollingFriction > btScalar(0)) continue;
    btSolverBody& a = m_tmpSolverBodyPool[contact.m_solverBodyIdA];
    btSolverBody& b = m_tmpSolverBodyPool[contact.m_solverBodyIdB];
    btCollisionObject* object_a = a.m_originalBody;
    btCollisionObject* object_b = b.m_originalBody;
    const btVector3 rel_a = point.getPositionWorldOnA() - a.getWorldTransform().getOrigin();
    const btVector3 rel_b = point.getPositionWorldOnB() - b.getWorldTransform().getOrigin();
    addTorsionalFrictionConstraint(point.m_normalWorldOnB, contact.m_solverBodyIdA, contact.m_solverBodyIdB, k, point,
                                   point.m_combinedSpinningFriction, rel_a, rel_b, object_a, object_b, info.m_sor);
  }
}

btScalar ContactSolver::solveSingleIteration(int iteration, btCollisionObject** bodies, int num_bodies,
                                             btPersistentManifold** manifolds, int num_manifolds,
                                             btTypedConstraint** constraints, int num_constraints,
                                             const btContactSolverInfo& info, btIDebugDraw* debug_draw) {
  const btScalar residual = btSequentialImpulseConstraintSolver::solveSingleIteration(
      iteration, bodies, num_bodies, manifolds, num_manifolds, constraints, num_constraints, info, debug_draw);
  // Bullet solves contact and friction rows only in the first m_numIterations iterations.
  if (iteration >= info.m_numIterations) return residual;
  // Rolling friction rows (a torque limited by the rolling friction times the normal impulse)
  // have the same skip in Bullet, and the same fix.
  for (btConstraintArray* pool : {&m_tmpSolverContactFrictionConstraintPool, &m_tmpSolverContactRollingFrictionConstraintPool}) {
    const int count = pool->size();
    for (int k = 0; k < count; ++k) {
      btSolverConstraint& friction = (*pool)[k];
      if (friction.m_appliedImpulse == btScalar(0)) continue;
      const btSolverConstraint& normal = m_tmpSolverContactConstraintPool[friction.m_frictionIndex];
      if (normal.m_appliedImpulse > btScalar(0)) continue;  // Bullet clamped this one itself
      friction.m_lowerLimit = btScalar(0);
      friction.m_upperLimit = btScalar(0);
      m_resolveSingleConstraintRowGeneric(m_tmpSolverBodyPool[friction.m_solverBodyIdA],
                                          m_tmpSolverBodyPool[friction.m_solverBodyIdB], friction);
      ++released_;
    }
  }
  if (info.m_solverMode & SOLVER_USE_2_FRICTION_DIRECTIONS) clampToFrictionDisc();
  return residual;
}

void ContactSolver::setImpulse(btSolverConstraint& row, btScalar impulse) {
  row.m_lowerLimit = row.m_upperLimit = impulse;
  m_resolveSingleConstraintRowGeneric(m_tmpSolverBodyPool[row.m_solverBodyIdA], m_tmpSolverBodyPool[row.m_solverBodyIdB], row);
}

void ContactSolver::clampToFrictionDisc() {
  btConstraintArray& pool = m_tmpSolverContactFrictionConstraintPool;
  const int count = pool.size();
  for (int k = 0; k + 1 < count; ++k) {
    btSolverConstraint& first = pool[k];
    btSolverConstraint& second = pool[k + 1];
    if (second.m_frictionIndex != first.m_frictionIndex) continue;  // one row only (not a pair)
    ++k;
    const btSolverConstraint& normal = m_tmpSolverContactConstraintPool[first.m_frictionIndex];
    const btScalar limit = first.m_friction * std::max(normal.m_appliedImpulse, btScalar(0));
    if (sliding_[std::size_t(first.m_frictionIndex)]) {
      // Sliding: the row along the slip first (Bullet clamps it to +-limit itself), the row
      // across it gets what the disc leaves, so the motion meets mu * N along its slip, as with
      // a single row.
      const btScalar budget = btSqrt(std::max(limit * limit - first.m_appliedImpulse * first.m_appliedImpulse, btScalar(0)));
      if (btFabs(second.m_appliedImpulse) <= budget) continue;
      setImpulse(second, second.m_appliedImpulse > btScalar(0) ? budget : -budget);
    } else {
      // Sticking: the "slip" direction holds this step's gravity, which other contacts may carry
      // (a block against a fence); the friction the solve found is kept in its direction, within
      // mu * N.
      const btScalar magnitude = btSqrt(first.m_appliedImpulse * first.m_appliedImpulse +
                                        second.m_appliedImpulse * second.m_appliedImpulse);
      if (magnitude <= limit) continue;
      const btScalar scale = limit / magnitude;
      setImpulse(first, first.m_appliedImpulse * scale);
      setImpulse(second, second.m_appliedImpulse * scale);
    }
    ++clamped_;
  }
}

}  // namespace thx::phys
