#pragma once
// Normal-map contact rule (docs/design.md §1, Eq. 1 and Eq. 2), applied to one Bullet manifold
// point between a flat textured plane and another body, after collision detection and before the
// solver:
//  - the contact normal becomes the texture's sampled normal n_s at the contact (Eq. 1), in world
//    frame, pointing from the plane towards the object;
//  - for a sphere, both contact points move to q = c - r n_s (Eq. 2): the push then goes through
//    the centre, so the ball rolls down the virtual slope instead of being spun backwards by the
//    torque of a tilted force applied at its bottom point;
//  - other shapes keep their points and change the normal only.
#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/NarrowPhaseCollision/btManifoldPoint.h>
#include <BulletDynamics/ConstraintSolver/btContactSolverInfo.h>

#include "textures/textured_surface.hpp"

namespace thx::phys {

struct NormalMapOptions {
  // Sampled normals tilted further than this from the plane's normal are clamped to it (keeping
  // their azimuth). Why: the solver only holds the object along n_s, so a near-grazing n_s gives
  // almost no support against gravity and the object sinks through the flat plane; the clamp
  // bounds the virtual slope (docs/physics.md, "near-grazing normals"). 90 disables it.
  double max_tilt_deg = 75.0;
  // Hold the object's height on the flat plane while it moves sideways (see applyNormalMap).
  bool hold_height = true;
};

// What the rewrite needs to know about the step (from the world's solver and dispatch info).
struct StepContext {
  double dt_s = 1e-3;
  double erp = 0.2;                            // btContactSolverInfo::m_erp (shallow contacts)
  double split_penetration_threshold = -0.04;  // deeper than this Bullet corrects by split impulse
  // The body the surface belongs to where it moves (a textured box's faces, ball_on_object_faces.hpp):
  // the object's velocity is taken relative to it. nullptr: a fixed surface.
  const btCollisionObject* surface_body = nullptr;
};
// The step's context from the world's solver settings and its step.
StepContext stepContextOf(const btContactSolverInfo& solver, double dt_s);

// n (unit) tilted at most max_tilt_deg from the unit vector `axis`, keeping its azimuth about it
// (90 leaves it as it is); a normal straight across the axis becomes the axis.
Eigen::Vector3d clampTilt(const Eigen::Vector3d& n, const Eigen::Vector3d& axis, double max_tilt_deg);

// The sampled normal at plane-local (x, y), clamped to max_tilt, in the plane frame.
Eigen::Vector3d clampedSampledNormal(const tex::TexturedSurface& surface, double x_local, double y_local,
                                     double max_tilt_deg);

// The rule once the steering normal is known, shared by the plane and the mesh
// (mesh_contact.hpp): `point`'s normal becomes n_world (unit, from the surface towards `other`);
// a sphere's points move to c - r n_world (Eq. 2); with hold_height, the distance is set so that
// the solver keeps the object on the geometry, whose unit normal there is n_geometric (the
// plane's; the flat triangle's on a mesh), as explained under applyNormalMap.
void steerContact(btManifoldPoint& point, bool surface_is_b, const Eigen::Vector3d& n_world,
                  const Eigen::Vector3d& n_geometric, const btCollisionObject& other, bool hold_height,
                  const StepContext& step);

// A ball of `other`: its sphere, or one of the balls a capsule sweeps along its axis
// (ball_on_object_faces.hpp), centred at `centre_world`.
struct ObjectBall {
  Eigen::Vector3d centre_world;
  double radius_m = 0.0;
};
// steerContact for a point made by `ball` of `other`: the point moves to its centre - r n_world,
// and the height held is taken against its centre's velocity (the lever arm of a ball's contact is
// along its normal, so its rolling does not enter).
void steerBallContact(btManifoldPoint& point, bool surface_is_b, const Eigen::Vector3d& n_world,
                      const Eigen::Vector3d& n_geometric, const ObjectBall& ball, const btCollisionObject& other,
                      bool hold_height, const StepContext& step);

// Rewrites `point` of a manifold in which the textured plane is body B (`plane_is_b`) or body A.
// `plane_to_world` is the plane body's world transform (the surface's local frame); `other` is the
// object touching the plane.
//
// hold_height: the solver only enforces v·n_s >= bias, so an object moving downhill the virtual
// slope looks separating and sinks into the flat plane until Baumgarte's bias catches up
// (|v| sinθ dt / erp: 1.2 mm at 0.9 m/s on 15°), and one moving uphill is lifted. The rewrite
// therefore also sets the point's distance so that the solver's bias along n_s equals what keeps
// the object's height: with v_t the pre-solve velocity along the plane (of the centre for a
// sphere, of the contact point otherwise) and b_g the bias the flat contact had along n_g,
//   v·n_s >= R = b_g cosθ + v_t·n_s   <=>   v·n_g >= b_g.
// This is Eq. 1's intent (the plane carries the weight, the texture steers the push).
void applyNormalMap(btManifoldPoint& point, bool plane_is_b, const Eigen::Isometry3d& plane_to_world,
                    const tex::TexturedSurface& surface, const btCollisionObject& other,
                    const NormalMapOptions& options, const StepContext& step = {});

// Marks a point a mean slope has leaned (leanReliefContact, mesh_contact.hpp's leanChartContact):
// a point kept from the last step is leaned once. Bullet's own flags use the low five bits; a
// point Bullet replaces with a new one takes the new one's flags.
inline constexpr int kLeanedContactFlag = 1 << 12;

// The lean itself, shared by the plane (leanReliefContact) and a mesh's chart (mesh_contact.hpp's
// leanChartContact): `point`'s own normal (towards the object, its surface's frame, whose normal
// there is `up`; unleaned first if the point carries kLeanedContactFlag) tilted by `lean` (that
// frame, tangential) as by any slope, n - (n . up) lean, clamped to max_tilt_deg from `up`, the gap
// held along the point's own normal (steerContact). `surface_to_world` turns the frame's
// directions into the world's.
void leanContact(btManifoldPoint& point, bool surface_is_b, const Eigen::Matrix3d& surface_to_world,
                 const Eigen::Vector3d& up, const Eigen::Vector3d& lean, const btCollisionObject& other,
                 double max_tilt_deg, bool hold_height, const StepContext& step);

// Leans `point`, made on a relief plane that stands for a normal-mapped plane (the relief its
// normals integrate to: periodic, so level; PhysicsWorld::addTexturedObjectsRelief), by the map's
// mean slope `lean_local` ((dh/dx, dh/dy, 0) in the plane frame): its normal tilted as by any
// slope, n - (n . z) lean, the gap held along its own normal (steerContact with hold_height), so
// an object meets the virtual slope as on the normal-mapped plane and keeps its height. Nothing
// for a zero lean.
void leanReliefContact(btManifoldPoint& point, bool plane_is_b, const Eigen::Isometry3d& plane_to_world,
                       const Eigen::Vector3d& lean_local, const btCollisionObject& other, const NormalMapOptions& options,
                       const StepContext& step = {});

}  // namespace thx::phys
