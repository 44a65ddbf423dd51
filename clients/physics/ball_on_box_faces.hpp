#pragma once
// A plain ball or a capsule against a textured box (issue 29, "a textured object against another
// object"): the box's faces met as a relief mesh's triangles are (mesh_contact.hpp), the object
// lifted onto the box's relief as a ball meets it. The box is a mesh of its six faces laid as its
// face texture is read (meshes/textured_box_mesh.hpp). A capsule is its segment swept by a ball,
// so it is met as the balls on its segment that meet each triangle (capsule_balls.hpp: where the
// segment comes nearest beside the triangle, and over it the ball of least lifted gap on each half
// of its run); a sphere is its one ball.
// Each step every such ball's point on each of the twelve triangles within the breaking threshold
// is found as Bullet's sphere-triangle algorithm finds it on a mesh (the nearest point of the
// triangle, the normal from it to the ball's centre), kept between steps as Bullet keeps a mesh's,
// and every point is rewritten by applyBallMeshContact for the ball that made it (the axis point
// nearest its place on the object), with the box's frame and its velocity
// (StepContext::surface_body). So a marble rolls along a grooved box's grooves and off its edge
// (ballPastCrease) as it does on the same relief laid on a box mesh, and a capsule lying in a
// groove rests on its rims as a ball's cross-section does.
//
// Why not the relief algorithm's plain-ball rule on the box's chart (relief_collision.hpp): tried
// on 2026-12-04, it threw a marble rolling off the grooved board's edge up at 0.45 m/s, and rode
// 0.32 mm too low on its top; a plain ball on a relief mesh has always kept Bullet's points, lifted.
// Nor its rod rules for a capsule: the pen's upright capsule pushing the grooved block met the
// block's top face at its edge, where a groove wall's tilted normal made the capsule's far side
// the contact point, 1.75 mm deep where the raster read 0.23 mm, and threw the block at 0.22 m/s.
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
  double texel_m = 0.0;         // the finer of the texture's two texel sizes on a face
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

// A plain ball (no bump map) or a capsule: the shapes met as balls.
bool meetsBoxFacesAsBalls(const btCollisionShape& shape);

class BallOnBoxFacesAlgorithm : public ManifoldAlgorithm {
 public:
  // `box_first`: body0 is the box; the other body meetsBoxFacesAsBalls. `faces` and `catalog`
  // outlive the algorithm (the world's).
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
