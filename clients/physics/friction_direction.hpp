#pragma once
// Friction along the slip at any slip speed.
//
// Bullet's default solver mode takes one friction direction per contact point: the tangential
// relative velocity, but only when that exceeds sqrt(FLT_EPSILON) = 0.35 mm/s; below it falls
// back to a fixed tangent (btPlaneSpace1: -y on a level plane), so a slow slide along x meets no
// friction at all. A ball stopped by rolling friction slid on at 0.25-0.31 mm/s, and every
// resting contact read a slip of that order (docs/physics.md, "Rest").
//
// With SOLVER_ENABLE_FRICTION_DIRECTION_CACHING set, Bullet uses a point's m_lateralFrictionDir1
// as given when the point's BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED flag is set. This sets
// both, every step, for every point: the direction is the same tangential relative velocity Bullet
// computes (velocities plus this step's external force and torque impulses, at the point), for
// any slip above kMinSlip; Bullet's fixed tangent only for a slip below it, where no direction is
// meaningful. Above 0.35 mm/s the result is Bullet's own direction.
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

namespace thx::phys {

inline constexpr double kMinSlip_m_per_s = 1e-9;

// Every point of the manifold; dt_s is the step the solver is about to take.
void alignFrictionWithSlip(btPersistentManifold& manifold, double dt_s);

}  // namespace thx::phys
