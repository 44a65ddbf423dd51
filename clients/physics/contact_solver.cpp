#include "clients/physics/contact_solver.hpp"

#include <initializer_list>

namespace thx::phys {

btScalar ContactSolver::solveGroup(btCollisionObject** bodies, int num_bodies, btPersistentManifold** manifolds,
                                   int num_manifolds, btTypedConstraint** constraints, int num_constraints,
                                   const btContactSolverInfo& info, btIDebugDraw* debug_draw,
                                   btDispatcher* dispatcher) {
  released_ = 0;
  return btSequentialImpulseConstraintSolver::solveGroup(bodies, num_bodies, manifolds, num_manifolds, constraints,
                                                         num_constraints, info, debug_draw, dispatcher);
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
  return residual;
}

}  // namespace thx::phys
