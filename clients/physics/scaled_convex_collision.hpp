#pragma once
// Bullet's GJK + EPA for convex pairs, run on copies of the two shapes scaled up to metre size.
//
// Bullet's convex-convex path (btConvexConvexAlgorithm) has absolute tolerances tuned for
// metre-sized shapes: its btVoronoiSimplexSolver treats support points within
// sqrt(1e-4) m = 1 cm as one, and EPA stops on absolute errors of the same order. With the
// haptic scenes' centimetre shapes and millimetre overlaps GJK stops on a wrong feature: measured
// over random 0.05-2 mm overlaps, 20 % of sphere-box, 52 % sphere-cylinder and 63 % box-cylinder
// pairs read "apart", and a ball rolled into a box wall sank 2 mm in (docs/physics.md, "Shape
// pairs"). The same query on the same poses scaled by 100 is accurate, so this algorithm does
// exactly that, for one pair only: it builds the two shapes scaled by kScale (radii, half
// extents, margins) and their poses scaled about the pair's midpoint, runs Bullet's
// btGjkPairDetector with btGjkEpaPenetrationDepthSolver there, and reports the contact scaled
// back (point / kScale, depth / kScale; the normal is unchanged). Everything else -- the
// manifold, its point matching and refresh, the solver -- is Bullet's, in SI units.
//
// Registered (registerScaledConvexCollision) for every pair of sphere, box, capsule and cylinder
// that Bullet has no exact algorithm for: sphere-box, sphere-cylinder, box-cylinder,
// capsule-box, capsule-cylinder, cylinder-cylinder. Box-box (btBoxBoxDetector), sphere-sphere,
// sphere-capsule and capsule-capsule stay Bullet's own (analytic, exact at any scale).
#include "clients/physics/manifold_algorithm.hpp"

namespace thx::phys {

class ScaledConvexAlgorithm : public ManifoldAlgorithm {
 public:
  // Shapes of centimetres become metres: the size Bullet's tolerances are made for.
  static constexpr double kScale = 100.0;

  using ManifoldAlgorithm::ManifoldAlgorithm;

  void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                        const btDispatcherInfo& info, btManifoldResult* result) override;

  struct CreateFunc : btCollisionAlgorithmCreateFunc {
    btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                   const btCollisionObjectWrapper* body0,
                                                   const btCollisionObjectWrapper* body1) override {
      return create<ScaledConvexAlgorithm>(ci, body0, body1);
    }
  };
};

// True for the pairs this algorithm handles (either order).
bool usesScaledConvex(int shape_type_0, int shape_type_1);

// Registers the algorithm for those pairs in both orders. The create function is static: it
// outlives any dispatcher.
void registerScaledConvexCollision(btCollisionDispatcher& dispatcher);

}  // namespace thx::phys
