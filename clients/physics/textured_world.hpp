#pragma once
// A btDiscreteDynamicsWorld that knows about textured planes.
//
// Normal-map mode lives here: performDiscreteCollisionDetection() runs Bullet's own collision
// detection, then rewrites every manifold point touching a registered normal-mapped plane
// (normal_map_contact.hpp), textured mesh (mesh_contact.hpp) or relief standing for a leaning normal
// map (leanReliefContact) before the solver runs. Doing it here rather than in
// gContactAddedCallback reaches every point on every step, including points Bullet keeps from
// earlier steps, and sees world positions after refreshContactPoints (docs/design.md §7 fact 7).
//
// Relief mode needs nothing from the world beyond the collision algorithms registered on its
// dispatcher (relief_collision.hpp); PhysicsWorld wires both.
#include <BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h>

#include <unordered_map>
#include <utility>
#include <vector>

#include "clients/physics/mesh_contact.hpp"
#include "clients/physics/normal_map_contact.hpp"
#include "clients/physics/rest_detector.hpp"
#include "textures/textured_surface.hpp"

namespace thx::phys {

class TexturedWorld : public btDiscreteDynamicsWorld {
 public:
  TexturedWorld(btDispatcher* dispatcher, btBroadphaseInterface* broadphase, btConstraintSolver* solver,
                btCollisionConfiguration* configuration)
      : btDiscreteDynamicsWorld(dispatcher, broadphase, solver, configuration) {}

  // `plane` is a static body whose frame is the surface's plane frame (its shape is normally a
  // btStaticPlaneShape with normal +z). The surface (and its map) must outlive the registration.
  void addNormalMapPlane(const btCollisionObject* plane, const tex::TexturedSurface* surface,
                         const NormalMapOptions& options = {});
  void removeNormalMapPlane(const btCollisionObject* plane);
  // `body` is a static body whose shape is `mesh`'s triangles in order (one part), its frame the
  // mesh's; its contacts are steered by mesh_contact.hpp. The mesh (and any texture in
  // `options`) must outlive the registration.
  void addTexturedMesh(const btCollisionObject* body, const mesh::TexturedMesh* mesh, const MeshContactOptions& options);
  // `relief` is a static relief plane standing for a normal map that leans on average (its mean
  // slope `lean_local`, (dh/dx, dh/dy, 0) in the plane frame, which the periodic relief cannot
  // hold): its contacts lean by it (leanReliefContact). PhysicsWorld::addTexturedObjectsRelief.
  void addLeaningRelief(const btCollisionObject* relief, const Eigen::Vector3d& lean_local, const NormalMapOptions& options = {});

  // Bullet's detection, then the normal-map rewrite, then (with the solver's
  // SOLVER_ENABLE_FRICTION_DIRECTION_CACHING) every point's friction along its slip
  // (friction_direction.hpp).
  void performDiscreteCollisionDetection() override;

  // Rest (rest_detector.hpp): bodies at rest go to sleep by Bullet's island rules. Bodies with
  // DISABLE_DEACTIVATION (the pen) never do.
  void setRestOptions(const RestOptions& options) { rest_ = options; }
  const RestOptions& restOptions() const { return rest_; }

  // Contact points rewritten by the last step (for tests and statistics).
  long long rewrittenPoints() const { return rewritten_; }

 private:
  struct NormalMapPlane {
    const btCollisionObject* body;
    const tex::TexturedSurface* surface;
    NormalMapOptions options;
  };
  struct TexturedMeshBody {
    const btCollisionObject* body;
    ContactMesh mesh;
    MeshContactOptions options;
  };
  struct LeaningRelief {
    const btCollisionObject* body;
    Eigen::Vector3d lean_local;
    NormalMapOptions options;
  };
  void rewriteNormalMapContacts();
  void rewriteLeaningReliefContacts();
  void rewriteMeshContacts();
  StepContext stepContext();
  void updateActivationState(btScalar time_step) override;
  // Bullet's island manager wakes every body that shares a manifold with an active kinematic
  // body, even a manifold with no contact point (the pen's bounding box near a resting ball): a
  // resting body beside the pen never slept. During the solve a kinematic body with no contact
  // point in any manifold is marked asleep, so it wakes only what it touches.
  void solveConstraints(btContactSolverInfo& info) override;

  std::vector<NormalMapPlane> planes_;
  std::vector<TexturedMeshBody> meshes_;
  std::vector<LeaningRelief> leaning_reliefs_;
  long long rewritten_ = 0;
  // Each ball's crease points before this step's detection (applyBallMeshManifold), by manifold.
  std::vector<std::pair<const btPersistentManifold*, CreaseSides>> crease_sides_;
  RestOptions rest_;
  std::unordered_map<const btRigidBody*, RestDetector> rest_detectors_;
};

}  // namespace thx::phys
