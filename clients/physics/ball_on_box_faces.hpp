#pragma once
// A plain ball against a textured box (issue 29, "a textured object against another object"): the
// box's faces met as a relief mesh's triangles are (mesh_contact.hpp), the ball lifted onto the
// box's relief as its sphere meets it. The box is a mesh of its six faces laid as its face texture
// is read (meshes/textured_box_mesh.hpp); each step the ball's points on those twelve triangles
// are found as Bullet's sphere-triangle algorithm finds them on a mesh (the nearest point of each
// triangle within the breaking threshold, the normal from it to the centre), kept between steps as
// Bullet keeps a mesh's, and every point is rewritten by applyMeshContact with the box's frame and
// its velocity (StepContext::surface_body). So a marble rolls along a grooved box's grooves and
// off its edge (ballPastCrease) as it does on the same relief laid on a box mesh.
//
// Why not the relief algorithm's plain-ball rule on the box's chart (relief_collision.hpp): tried
// on 2026-12-04, it threw a marble rolling off the grooved board's edge up at 0.45 m/s, and rode
// 0.32 mm too low on its top; a plain ball on a relief mesh has always kept Bullet's points, lifted.
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletDynamics/ConstraintSolver/btContactSolverInfo.h>

#include <Eigen/Core>
#include <memory>
#include <unordered_map>

#include "clients/physics/manifold_algorithm.hpp"
#include "clients/physics/mesh_contact.hpp"
#include "clients/physics/textured_box.hpp"
#include "meshes/textured_mesh.hpp"
#include "textures/ball_on_relief.hpp"

namespace thx::phys {

// One textured box's faces as a relief mesh (built once per box: the ball's relief pyramid costs
// a millisecond or more at 512 texels).
struct BoxFaces {
  // `half_extents_m`: the whole box's (with Bullet's margin); `texture` must outlive this.
  BoxFaces(const Eigen::Vector3d& half_extents_m, const FaceTexture& texture);
  BoxFaces(const BoxFaces&) = delete;
  BoxFaces& operator=(const BoxFaces&) = delete;

  mesh::TexturedMesh mesh;
  ContactMesh contact;  // reads mesh
  tex::BallOnRelief ball_relief;
  MeshContactOptions options;  // reads the texture and ball_relief
};

// The faces of every textured box in one world, by its shape, and the world's solver settings
// (the rewrite's StepContext). PhysicsWorld fills it.
struct BoxFacesCatalog {
  void add(const btCollisionShape& box, const Eigen::Vector3d& half_extents_m, const FaceTexture& texture);
  const BoxFaces* find(const btCollisionShape& box) const;

  const btContactSolverInfo* solver = nullptr;

 private:
  std::unordered_map<const btCollisionShape*, std::unique_ptr<BoxFaces>> faces_;
};

class BallOnBoxFacesAlgorithm : public ManifoldAlgorithm {
 public:
  // `box_first`: body0 is the box. `faces` and `catalog` outlive the algorithm (the world's).
  BallOnBoxFacesAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* body0,
                          const btCollisionObjectWrapper* body1, bool box_first, const BoxFaces* faces,
                          const BoxFacesCatalog* catalog)
      : ManifoldAlgorithm(ci, body0, body1), box_first_(box_first), faces_(faces), catalog_(catalog) {}

  void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                        const btDispatcherInfo& info, btManifoldResult* result) override;

 private:
  bool box_first_;
  const BoxFaces* faces_;
  const BoxFacesCatalog* catalog_;
};

}  // namespace thx::phys
