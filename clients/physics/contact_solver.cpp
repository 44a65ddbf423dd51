#include "clients/physics/contact_solver.hpp"

#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <algorithm>
#include <initializer_list>

#include "clients/physics/textured_ball.hpp"

namespace thx::phys {

namespace {
// Whether a ball with a bump map (textured_ball.hpp) has a contact point among the manifolds.
bool holdsTexturedBall(btPersistentManifold* const* manifolds, int num_manifolds) {
  for (int m = 0; m < num_manifolds; ++m)
    if (manifolds[m]->getNumContacts() > 0 && (ballTextureOf(*manifolds[m]->getBody0()->getCollisionShape()) ||
                                               ballTextureOf(*manifolds[m]->getBody1()->getCollisionShape())))
      return true;
  return false;
}
}  // namespace

void ContactSolver::prepareSolve(int num_bodies, int num_manifolds) {
  released_ = 0;
  clamped_ = 0;
  shared_ = 0;
  btSequentialImpulseConstraintSolver::prepareSolve(num_bodies, num_manifolds);
}

btScalar ContactSolver::solveGroup(btCollisionObject** bodies, int num_bodies, btPersistentManifold** manifolds,
                                   int num_manifolds, btTypedConstraint** constraints, int num_constraints,
                                   const btContactSolverInfo& info, btIDebugDraw* debug_draw,
                                   btDispatcher* dispatcher) {
  btContactSolverInfo group_info = info;
  if (group_info.m_numIterations < textured_ball_iterations_ && holdsTexturedBall(manifolds, num_manifolds))
    group_info.m_numIterations = textured_ball_iterations_;
  return btSequentialImpulseConstraintSolver::solveGroup(bodies, num_bodies, manifolds, num_manifolds, constraints,
                                                         num_constraints, group_info, debug_draw, dispatcher);
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
  // Bullet converts the manifolds in order, each one's points in its cache's order.
  manifold_of_.resize(std::size_t(contacts));
  for (int k = 0, m = 0; k < contacts; ++k) {
    const auto* point = static_cast<const btManifoldPoint*>(m_tmpSolverContactConstraintPool[k].m_originalContactPoint);
    auto holds = [&](const btPersistentManifold& manifold) {
      if (manifold.getNumContacts() == 0) return false;
      const btManifoldPoint* first = &manifold.getContactPoint(0);
      return point >= first && point < first + manifold.getNumContacts();
    };
    while (m < num_manifolds && !holds(*manifolds[m])) ++m;
    manifold_of_[std::size_t(k)] = m < num_manifolds ? manifolds[m] : nullptr;
  }
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

void ContactSolver::shareStickingFriction() {
  btConstraintArray& pool = m_tmpSolverContactFrictionConstraintPool;
  const int count = pool.size();
  // Mostly nothing to share: no sticking point outside its disc (a body at rest).
  bool any_outside = false;
  for (int k = 0; k + 1 < count && !any_outside; ++k) {
    const btSolverConstraint& first = pool[k];
    const btSolverConstraint& second = pool[k + 1];
    if (second.m_frictionIndex != first.m_frictionIndex) continue;
    ++k;
    if (sliding_[std::size_t(first.m_frictionIndex)]) continue;
    const btScalar limit =
        first.m_friction * std::max(m_tmpSolverContactConstraintPool[first.m_frictionIndex].m_appliedImpulse, btScalar(0));
    any_outside = first.m_appliedImpulse * first.m_appliedImpulse + second.m_appliedImpulse * second.m_appliedImpulse > limit * limit;
  }
  if (!any_outside) return;
  // One point's two rows, as shareGroup reads them. `position`: where the friction acts on the
  // moving body (a static body's velocity needs no keeping).
  struct Pair {
    btSolverConstraint* first;
    btSolverConstraint* second;
    btVector3 position, normal;
    btScalar normal_impulse, distance;
    bool both_move;
    const btPersistentManifold* manifold;
  };
  thread_local std::vector<Pair> group;
  group.clear();
  // The loaded points of one manifold with one normal, within 10 um of one plane across it: a
  // flat face on a flat patch. Only there is the shared-out friction the same force and torque
  // (to a torque of 10 um times the friction moved, about an axis in the plane): a normal a
  // milliradian off drops a thousandth of the moved friction from the rows. A point without load
  // between them does not split the group: split, a grooved block at rest on a smooth chart (its
  // loaded points taking turns) jittered at up to 2.5e-5 m/s, 3.5e-7 whole. Points of several
  // manifolds of one pair (a textured box's groups) are not shared between: a grooved block
  // balanced on its outermost ridge 2 mm short of a slab's edge on its smooth chart rocked off it
  // and tipped over the edge in 0.3 s (normals equal to 1e-16), and with normals 1.4 mrad apart
  // allowed one sharing turned it at up to 5e-4 rad/s. Where both bodies move, the points on each
  // must also be one distance apart.
  auto sameFace = [&](const Pair& a, const Pair& b) {
    return a.manifold == b.manifold && a.manifold != nullptr &&
           (a.normal - b.normal).length2() < kSameNormal * kSameNormal &&
           btFabs((b.position - a.position).dot(a.normal)) < kSameHeight &&
           (!a.both_move || btFabs(a.distance - b.distance) < kSameHeight);
  };
  auto moves = [&](int body) { return !m_tmpSolverBodyPool[body].internalGetInvMass().fuzzyZero(); };
  auto flush = [&] {
    if (group.size() > 1) shareGroup(group);
    group.clear();
  };
  for (int k = 0; k + 1 < count; ++k) {
    btSolverConstraint& first = pool[k];
    btSolverConstraint& second = pool[k + 1];
    if (second.m_frictionIndex != first.m_frictionIndex) {  // one row only: not shared
      flush();
      continue;
    }
    ++k;
    const btSolverConstraint& contact = m_tmpSolverContactConstraintPool[first.m_frictionIndex];
    const auto& point = *static_cast<const btManifoldPoint*>(contact.m_originalContactPoint);
    const bool a_moves = moves(contact.m_solverBodyIdA), b_moves = moves(contact.m_solverBodyIdB);
    const Pair pair{&first,
                    &second,
                    a_moves ? point.getPositionWorldOnA() : point.getPositionWorldOnB(),
                    point.m_normalWorldOnB,
                    std::max(contact.m_appliedImpulse, btScalar(0)),
                    point.getDistance(),
                    a_moves && b_moves,
                    manifold_of_[std::size_t(first.m_frictionIndex)]};
    if (sliding_[std::size_t(first.m_frictionIndex)]) {
      flush();
      continue;
    }
    // A point without load has no friction to share (the disc takes all of it away).
    if (!(pair.normal_impulse > btScalar(0))) continue;
    if (!group.empty() && !sameFace(group.front(), pair)) flush();
    group.push_back(pair);
  }
  flush();
}

template <class Pairs>
void ContactSolver::shareGroup(Pairs& group) {
  // Only where a point's friction leaves its disc: elsewhere the solve's own answer stands.
  bool outside = false;
  btScalar total_normal = 0;
  btVector3 centre(0, 0, 0), force(0, 0, 0), normal(0, 0, 0);
  for (const auto& p : group) {
    const btScalar f1 = p.first->m_appliedImpulse, f2 = p.second->m_appliedImpulse;
    const btScalar limit = p.first->m_friction * p.normal_impulse;
    outside = outside || f1 * f1 + f2 * f2 > limit * limit;
    total_normal += p.normal_impulse;
    centre += p.position * p.normal_impulse;
    force += p.first->m_contactNormal1 * f1 + p.second->m_contactNormal1 * f2;
    normal += p.normal;
  }
  if (!outside || !(total_normal > btScalar(0))) return;
  centre /= total_normal;
  normal.normalize();
  // The twist about the normal through the centre of the normal impulses, and what the points
  // give to it per unit of spin.
  btScalar twist = 0, spin_weight = 0;
  for (const auto& p : group) {
    const btVector3 r = p.position - centre;
    const btVector3 f = p.first->m_contactNormal1 * p.first->m_appliedImpulse + p.second->m_contactNormal1 * p.second->m_appliedImpulse;
    twist += r.cross(f).dot(normal);
    const btVector3 r_in_plane = r - normal * normal.dot(r);
    spin_weight += p.normal_impulse * r_in_plane.length2();
  }
  const btScalar spin = spin_weight > btScalar(0) ? twist / spin_weight : btScalar(0);
  auto shared = [&](const auto& p) {
    return force * (p.normal_impulse / total_normal) + normal.cross(p.position - centre) * (p.normal_impulse * spin);
  };
  // Only where every point's share lies within its disc: where the load sits on one point and the
  // twist falls on the others, their shares can lie far outside, and the disc would take the
  // friction away (a block on Bullet's triangles by a slab's edge was carried 13 cm).
  for (const auto& p : group) {
    const btScalar limit = p.first->m_friction * p.normal_impulse * btScalar(1 + 1e-6);
    if (shared(p).length2() > limit * limit) return;
  }
  for (auto& p : group) {
    const btVector3 f = shared(p);
    setImpulse(*p.first, f.dot(p.first->m_contactNormal1));
    setImpulse(*p.second, f.dot(p.second->m_contactNormal1));
  }
  ++shared_;
}

void ContactSolver::clampToFrictionDisc() {
  shareStickingFriction();
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
