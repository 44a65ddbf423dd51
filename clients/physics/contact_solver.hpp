#pragma once
// Bullet's sequential-impulse solver with one correction: friction never outlives its normal
// impulse.
//
// In every iteration Bullet solves the normal rows, then each friction row clamped to
// ±μ·(that contact's current normal impulse) -- but it SKIPS a friction row whose normal impulse
// is zero (btSequentialImpulseConstraintSolver::solveSingleIteration, `if (totalImpulse > 0)`).
// A contact that carried load in an early iteration and lost it in a later one therefore keeps
// the friction impulse it had accumulated, with no normal force behind it. For a box whose
// corners take turns carrying the load (a box rocking on its four corners, as one does on a
// normal-mapped plane where the tilted normals act at its bottom face) that is systematic
// excess friction: measured 9 % more tangential than μ × normal impulse, a box sliding 12 %
// slower than g (tanθ − μ) / (1 + μ tanθ) (docs/physics.md).
//
// After each of Bullet's iterations this solver re-solves exactly those rows with the limits
// [0, 0], which removes their accumulated impulse.
//
// Second correction: spinning (torsional) friction without rolling friction. Bullet adds a
// contact's spinning-friction row (a torque about the normal, at most the combined spinning
// friction × the normal impulse) only inside `if (m_combinedRollingFriction > 0)`, so a body
// with spinning friction and no rolling friction spun on forever (the `default` scene's marble,
// 0.17 rad/s in a dip). convertContacts adds that row for such contacts, the same row Bullet
// builds (addTorsionalFrictionConstraint), so the solve is the same either way.
//
// Third: Coulomb's disc. With SOLVER_USE_2_FRICTION_DIRECTIONS (PhysicsWorld's default) each
// point has a row along its slip and one across it, each clamped by Bullet to +-mu N alone. After
// each iteration the pair is kept within mu N: for a point that slides (tangential speed before
// the solve, without gravity's impulse, above 1 mm/s) the row along the slip keeps its impulse
// and the row across gets what is left; for a sticking point both are scaled onto the disc. One
// row alone left the motion across the slip free (a ball on two walls crept along them at
// 0.28 mm/s); two rows scaled together made sliding boxes up to 66 % fast (docs/physics.md).
//
// Fourth, before the disc: sticking points share their friction. Where several loaded sticking
// points of one manifold have one normal and lie in one plane across it (a face on a flat patch)
// and any of them holds friction outside its disc, their friction is shared out afresh: each
// point takes the group's total in proportion to its normal impulse, plus its share of the
// group's twist about the normal (the same force and torque on both bodies, so the solve's
// velocities stay), where every share then lies within its disc. The sequential solve
// leaves such a group's friction holding a self-balancing part (a squeeze across the push) that
// no motion needs; scaled onto the disc it took its share of mu N, and a box pushed up Bullet's
// own slope at 0.911 of the weight that friction holds to 0.941 slid 0.27 mm in 0.3 s
// (tests/physics/test_box_relief_slope.cpp).
// Fifth: a solve whose contacts include a ball with a bump map's (textured_ball.hpp) runs more
// iterations (PhysicsWorld's default 150, against 10). Its points are found afresh each step
// (relief_collision.hpp), so the solve starts cold every step, and in ten iterations it left
// the ball moving: a bumpy ball on four bump tips loaded one pair, then the other, rocking at
// 0.8 mm/s on a plain box, and the grooved board's marble rolled on along its groove at 0.05 mm/s
// against its rolling friction (docs/physics.md, "Known gaps"); at 40: 0.008 mm/s, and asleep,
// but kept awake the ball still rocked on three tips in a six-step cycle at up to 0.3 mm/s, the
// third tip lifting 40 nm and landing; at 150 under 0.02 mm/s on flat ground.
// Only its island runs them (the bodies whose bounds, widened by Bullet's 2 cm breaking
// threshold, meet): PhysicsWorld has each island solved on its own, where Bullet batches small
// islands into one solve.
// Everything else is Bullet's.
#include <BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h>

#include <vector>

namespace thx::phys {

class ContactSolver : public btSequentialImpulseConstraintSolver {
 public:
  // Friction rows released in the last step's solves (for tests and statistics).
  long long releasedFrictionRows() const { return released_; }
  // Friction pairs scaled onto the disc in the last step's solves (for tests and statistics).
  long long clampedFrictionPairs() const { return clamped_; }
  // Groups of sticking points whose friction was shared out afresh in the last step's solves.
  long long sharedFrictionGroups() const { return shared_; }

  // Once a step, before its islands' solves: the statistics start afresh.
  void prepareSolve(int num_bodies, int num_manifolds) override;

  // Iterations for a solve whose contacts include a ball with a bump map's (below).
  void setTexturedBallIterations(int iterations) { textured_ball_iterations_ = iterations; }

  btScalar solveGroup(btCollisionObject** bodies, int num_bodies, btPersistentManifold** manifolds, int num_manifolds,
                      btTypedConstraint** constraints, int num_constraints, const btContactSolverInfo& info,
                      btIDebugDraw* debug_draw, btDispatcher* dispatcher) override;

 protected:
  void convertContacts(btPersistentManifold** manifolds, int num_manifolds, const btContactSolverInfo& info) override;
  btScalar solveSingleIteration(int iteration, btCollisionObject** bodies, int num_bodies,
                                btPersistentManifold** manifolds, int num_manifolds, btTypedConstraint** constraints,
                                int num_constraints, const btContactSolverInfo& info,
                                btIDebugDraw* debug_draw) override;

 private:
  // Sets a row's accumulated impulse (limits [impulse, impulse], one row solve).
  void setImpulse(btSolverConstraint& row, btScalar impulse);
  void clampToFrictionDisc();
  void shareStickingFriction();
  template <class Pairs>
  void shareGroup(Pairs& group);

  // A contact point slides when its tangential speed before the solve exceeds this.
  static constexpr btScalar kSlidingSpeed = btScalar(1e-3);
  // Normals this close (rad) and points this close along them (m) belong to one flat face (a
  // relief's texels on one slope read heights 0.3 um apart: its depth step).
  static constexpr btScalar kSameNormal = btScalar(1e-6);
  static constexpr btScalar kSameHeight = btScalar(1e-5);
  std::vector<bool> sliding_;  // per contact row of the current solve
  std::vector<const btPersistentManifold*> manifold_of_;  // per contact row of the current solve

  int textured_ball_iterations_ = 0;
  long long released_ = 0;
  long long clamped_ = 0;
  long long shared_ = 0;
};

}  // namespace thx::phys
