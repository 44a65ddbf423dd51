#pragma once
// Everything a Bullet simulation on a textured plane needs, owned in one place: collision
// configuration, dispatcher (with the relief algorithms registered), broadphase, solver, the
// TexturedWorld, and the shapes and bodies added through it. Defaults suit haptic scale
// (cm objects, mm texels): bodies sleep only by our rest criterion (rest_detector.hpp), 0.5 mm
// convex margins, multi-point plane contacts, friction along the slip at any speed.
// SI units throughout. Not real-time code: adding bodies allocates.
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>
#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "clients/physics/ball_texel_grid.hpp"
#include "clients/physics/box_ground.hpp"
#include "clients/physics/bullet_triangles.hpp"
#include "clients/physics/mesh_relief_chart.hpp"
#include "clients/physics/normal_map_contact.hpp"
#include "clients/physics/plain_plane.hpp"
#include "clients/physics/textured_ball.hpp"
#include "clients/physics/textured_box.hpp"
#include "clients/physics/textured_world.hpp"
#include "textures/textured_surface.hpp"

namespace thx::phys {

struct WorldOptions {
  Eigen::Vector3d gravity_m_per_s2{0.0, 0.0, -9.81};
  int solver_iterations = 10;
  // Iterations for a solve whose contacts include a ball with a bump map's (ContactSolver::
  // setTexturedBallIterations): its points are found afresh each step, so the solve starts cold
  // (at 40 a bumpy ball kept awake rocked on its tips at up to 0.3 mm/s; docs/physics.md, "Solver").
  int textured_ball_solver_iterations = 150;
  // Convex margin for boxes, capsules' and cylinders' GJK (Bullet's 4 cm default is far too big
  // at haptic scale; docs/design.md §7 fact 8).
  double convex_margin_m = 0.5e-3;
  // Sphere-box, sphere-cylinder, box-cylinder and the capsule-box/cylinder, cylinder-cylinder
  // pairs through ScaledConvexAlgorithm (Bullet's GJK/EPA on shapes scaled to metres); false:
  // Bullet's own btConvexConvexAlgorithm, which misses millimetre overlaps at this size.
  bool scaled_convex_pairs = true;
  // Friction along the slip at any slip speed (friction_direction.hpp); false: Bullet's fixed
  // tangent below 0.35 mm/s.
  bool friction_along_slip = true;
  // Two friction rows per contact point (along the slip and across it) whose joint impulse is
  // kept within mu * N (Coulomb's disc, contact_solver.hpp); false: Bullet's single row along
  // the slip, which leaves the motion across it free (a ball on two walls crept along them).
  bool friction_disc = true;
  // Bodies at rest sleep (rest_detector.hpp); disabled: no body ever sleeps.
  RestOptions rest;
};

struct BodyMaterial {
  double friction = 0.5;
  double restitution = 0.0;
  double rolling_friction = 0.0;
  // Spinning (torsional) friction, a length like rolling friction: the torque about a contact's
  // normal is at most the pair's value (Bullet's rule, delta_a * mu_b + delta_b * mu_a) times
  // the normal force. Applied with or without rolling friction (contact_solver.hpp).
  double spinning_friction = 0.0;
};

class PhysicsWorld {
 public:
  explicit PhysicsWorld(const WorldOptions& options = {});
  ~PhysicsWorld();
  PhysicsWorld(const PhysicsWorld&) = delete;
  PhysicsWorld& operator=(const PhysicsWorld&) = delete;

  TexturedWorld& world() { return *world_; }
  const WorldOptions& options() const { return options_; }

  // Static planes at the surface's plane frame (mapping.plane_to_world). The surface and its map
  // must outlive this world. On the plain plane a textured box or a ball with a bump map meets it
  // with its texture (plain_plane.hpp); on a normal-mapped one, as its coarse shape, its points
  // rewritten by the normal map, unless addTexturedObjectsRelief gives it a relief to meet.
  btRigidBody& addPlainPlane(const Eigen::Isometry3d& plane_to_world, const BodyMaterial& material);
  btRigidBody& addNormalMapPlane(const tex::TexturedSurface& surface, const BodyMaterial& material,
                                 const NormalMapOptions& options = {});
  btRigidBody& addReliefPlane(const tex::TexturedSurface& surface, const BodyMaterial& material);
  // The textured objects (boxes with faces, balls with bump maps) meet `relief` instead of `plane`
  // (a body from addNormalMapPlane): a relief plane at `relief`'s mapping standing for the plane's
  // normal map, the relief its normals integrate to (tex::reliefFromNormals), so both textures
  // shape their contacts as on a relief plane. Every other body meets the normal-mapped plane as
  // before (a broadphase filter keeps each pair to its own plane). A map that leans on average
  // (`mean_slope`, dh/dx and dh/dy in the plane frame, beyond tex::kLevelMeanSlope) leans the
  // relief's contacts by it, their heights held (leanReliefContact), as the plane's normals lean.
  // Add it before the first step (the filter decides when a pair is first found). `relief` must
  // outlive this world.
  btRigidBody& addTexturedObjectsRelief(const btRigidBody& plane, const tex::TexturedSurface& relief,
                                        const Eigen::Vector2d& mean_slope, const BodyMaterial& material,
                                        const NormalMapOptions& options = {});
  // A static textured mesh (meshes/textured_mesh.hpp, frames built) at `pose` (the mesh's frame
  // in the world): Bullet's btBvhTriangleMeshShape over its triangles, each contact steered by the
  // smooth surface and the texture (mesh_contact.hpp); with a relief map, a box (textured or not),
  // capsule or cylinder meets it on the chart under it as on the relief plane, a textured box's
  // relief shaping the contact too (mesh_relief_chart.hpp, relief_collision.hpp). The mesh
  // and any texture in `options` must outlive this world.
  btRigidBody& addTexturedMesh(const mesh::TexturedMesh& mesh, const Eigen::Isometry3d& pose,
                               const BodyMaterial& material, const MeshContactOptions& options = {});
  // Any static collision shape (heightfield, mesh ...), for comparisons; the world owns it.
  btRigidBody& addStaticShape(std::unique_ptr<btCollisionShape> shape, const Eigen::Isometry3d& pose,
                              const BodyMaterial& material);

  // Dynamic bodies; pose = centre of mass. Capsule and cylinder axes lie along the body's local z;
  // half_length: capsule = half the distance between cap centres, cylinder = half its height.
  btRigidBody& addSphere(double radius_m, double mass_kg, const Eigen::Isometry3d& pose, const BodyMaterial& material);
  btRigidBody& addBox(const Eigen::Vector3d& half_extents_m, double mass_kg, const Eigen::Isometry3d& pose,
                      const BodyMaterial& material);
  // A box whose faces carry a relief map (textured_box.hpp; the map must outlive this world): on a
  // relief plane (and the relief standing for a normal-mapped plane: addTexturedObjectsRelief), on
  // a mesh's chart and against another box or a ball with a bump map (box_ground.hpp) both
  // textures shape the contact; a plain ball or a capsule meets its faces' relief
  // (ball_on_object_faces.hpp); elsewhere it collides as the plain box.
  btRigidBody& addTexturedBox(const Eigen::Vector3d& half_extents_m, double mass_kg, const Eigen::Isometry3d& pose,
                              const BodyMaterial& material, const FaceTexture& texture);
  // A ball with a bump map (textured_ball.hpp; the map must outlive this world): on a relief plane
  // (and the relief standing for a normal-mapped plane: addTexturedObjectsRelief), on a mesh's
  // chart and against a box (box_ground.hpp) both textures shape the contact; elsewhere it
  // collides as the plain ball.
  btRigidBody& addTexturedSphere(double radius_m, double mass_kg, const Eigen::Isometry3d& pose,
                                 const BodyMaterial& material, const FaceTexture& texture);
  btRigidBody& addCapsule(double radius_m, double half_length_m, double mass_kg, const Eigen::Isometry3d& pose,
                          const BodyMaterial& material);
  btRigidBody& addCylinder(double radius_m, double half_length_m, double mass_kg, const Eigen::Isometry3d& pose,
                           const BodyMaterial& material);

  // Exactly one internal step of dt_s (no Bullet sub-stepping or interpolation).
  void step(double dt_s);

 private:
  btRigidBody& addBody(std::unique_ptr<btCollisionShape> shape, double mass_kg, const Eigen::Isometry3d& pose,
                       const BodyMaterial& material);

  // Which plane a pair meets where a relief stands in for a normal-mapped plane (physics_world.cpp).
  struct TexturedObjectsFilter;

  WorldOptions options_;
  std::unique_ptr<TexturedObjectsFilter> textured_objects_filter_;  // declared before the world that reads it
  std::unique_ptr<btDefaultCollisionConfiguration> configuration_;
  std::unique_ptr<BoxGroundRegistration> box_ground_funcs_;  // the dispatcher points at them
  std::unique_ptr<PlainPlaneRegistration> plain_plane_funcs_;  // and at these
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btDbvtBroadphase> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<TexturedWorld> world_;
  // The meshes' triangles (declared before shapes_: the shapes that read them go first).
  std::vector<std::unique_ptr<BulletTriangles>> triangle_arrays_;
  std::vector<std::unique_ptr<FaceTexture>> face_textures_;  // the textured boxes' (their shapes point here)
  std::vector<std::unique_ptr<const BallTexelGrid>> ball_grids_;      // the textured balls' texel grids
  std::vector<std::unique_ptr<GriddedBallTexture>> ball_textures_;    // and their textures (their shapes point here)
  std::vector<std::unique_ptr<MeshRelief>> mesh_reliefs_;    // the relief meshes' (their shapes point here)
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
};

// Helpers for reading state back in SI / Eigen.
Eigen::Vector3d positionOf(const btRigidBody& body);
Eigen::Vector3d velocityOf(const btRigidBody& body);
Eigen::Vector3d angularVelocityOf(const btRigidBody& body);
void setVelocity(btRigidBody& body, const Eigen::Vector3d& v_m_per_s, const Eigen::Vector3d& w_rad_per_s);

}  // namespace thx::phys
