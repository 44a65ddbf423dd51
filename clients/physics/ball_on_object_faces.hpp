#pragma once
// A plain ball or a capsule against a textured object (issue 29, "a textured object against
// another object"): the object's surface met as a relief mesh's triangles are (mesh_contact.hpp),
// the ball or capsule lifted onto its relief as a ball meets it. The textured object is a mesh of
// its surface laid as its texture is read: a box's six faces (meshes/textured_box_mesh.hpp), a
// ball with a bump map as its cube-sphere (meshes/textured_ball_mesh.hpp; its relief is met on
// the ball's curvature, MeshContactOptions::sphere_radius_m). A capsule is its segment swept by a
// ball, so it is met as the balls on its segment: on a box's faces those that meet each triangle
// (capsule_balls.hpp: where the segment comes nearest beside the triangle, and over it the ball of
// least lifted gap on each half of its run); on a ball, whose triangles are far smaller than the
// run, the least on each half of the segment's whole run within reach, searched once. A sphere is
// its one ball, its lifted gap read once from the triangle nearest it.
// Each step every such ball's point on its triangle within the breaking threshold (the triangles
// the object's bounding box meets, asked of a Bullet BVH of the surface) is found as Bullet's
// sphere-triangle algorithm finds it on a mesh (the nearest point of the triangle, the normal from
// it to the ball's centre) and entered with the ball's lifted gap (a full manifold keeps its
// deepest), kept between steps as Bullet keeps a mesh's, and every point is rewritten by
// applyBallMeshContact for the ball that made it (kept in the point: ballCentreOfPoint), with the
// textured object's frame and its velocity (StepContext::surface_body). So a marble rolls along a
// grooved box's grooves and off its edge (ballPastCrease) as it does on the same relief laid on a
// box mesh, a capsule lying in a groove rests on its rims as a ball's cross-section does, and the
// pen pushing a dimpled ball meets its dimples. Where a ball's lift has a crease under it (a
// groove's floor, the two rims of a groove narrower than the ball), a sphere gets a point on each
// side of it (applyBallMeshManifold) and a capsule at the balls at the two ends of its run
// (splitCapsuleAtCreases), so each rests in a groove as in a wedge.
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
#include <cstdint>
#include <memory>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include "clients/physics/manifold_algorithm.hpp"
#include "clients/physics/mesh_contact.hpp"
#include "clients/physics/object_ground.hpp"
#include "clients/physics/textured_box.hpp"
#include "meshes/textured_mesh.hpp"
#include "textures/ball_on_relief.hpp"

namespace thx::phys {

// One textured object's surface as a relief mesh (built once per object: the ball's relief pyramid
// costs a millisecond or more at 512 texels, the cube-sphere 9 ms).
struct ObjectFaces {
  // `texture` must outlive this; `sphere_radius_m`: the smooth surface's, for a ball (0: flat faces).
  ObjectFaces(std::unique_ptr<ObjectGround> surface, const FaceTexture& texture, double sphere_radius_m);
  ObjectFaces(const ObjectFaces&) = delete;
  ObjectFaces& operator=(const ObjectFaces&) = delete;

  // The mesh, what the contacts walk on, its BVH, and its chart for other objects (box_ground.hpp).
  std::unique_ptr<ObjectGround> ground;
  const mesh::TexturedMesh& mesh;  // ground's
  const ContactMesh& contact;      // ground's
  tex::BallOnRelief ball_relief;
  MeshContactOptions options;  // reads the texture and ball_relief
  double texel_m = 0.0;         // the finer of the texture's two texel sizes where it is laid
};

// A textured box's six faces. `half_extents_m`: the whole box's (with Bullet's margin).
std::unique_ptr<ObjectFaces> boxFaces(const Eigen::Vector3d& half_extents_m, const FaceTexture& texture);
// A ball's bump-mapped surface, as a cube-sphere of `cells` quads along each face's edge.
std::unique_ptr<ObjectFaces> ballFaces(double radius_m, const FaceTexture& texture, int cells = 24);

// The surfaces of every textured box and textured ball in one world, by its shape, and the world's
// solver settings (the rewrite's StepContext). PhysicsWorld fills it.
struct ObjectFacesCatalog {
  void addBox(const btCollisionShape& box, const Eigen::Vector3d& half_extents_m, const FaceTexture& texture);
  void addBall(const btCollisionShape& ball, double radius_m, const FaceTexture& texture);
  const ObjectFaces* find(const btCollisionShape& shape) const;
  // Its surface as the ground another object's chart is laid on; nullptr for a shape not here.
  const ObjectGround* ground(const btCollisionShape& shape) const;

  const btContactSolverInfo* solver = nullptr;

 private:
  std::unordered_map<const btCollisionShape*, std::unique_ptr<ObjectFaces>> faces_;
};

// A plain ball (no bump map) or a capsule: the shapes met as balls.
bool meetsFacesAsBalls(const btCollisionShape& shape);

// The centre (the object's frame) of the ball of `object` (a plain ball or a capsule) that made a
// point of BallOnObjectFacesAlgorithm's manifold, whose body A is the object: kept in the point.
Eigen::Vector3d ballCentreOfPoint(const btManifoldPoint& point, const btCollisionShape& object);

class BallOnObjectFacesAlgorithm : public ManifoldAlgorithm {
 public:
  // `faces_first`: body0 is the textured object; the other body meetsFacesAsBalls. `faces` and
  // `catalog` outlive the algorithm (the world's).
  BallOnObjectFacesAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* body0,
                          const btCollisionObjectWrapper* body1, bool faces_first, const ObjectFaces* faces,
                          const ObjectFacesCatalog* catalog)
      : ManifoldAlgorithm(ci, body0, body1), faces_first_(faces_first), faces_(faces), catalog_(catalog) {}

  void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                        const btDispatcherInfo& info, btManifoldResult* result) override;

  // The object's segment in its own frame (its balls' centres): a capsule's axis, a sphere's centre.
  struct ObjectAxis {
    Eigen::Vector3d half_m = Eigen::Vector3d::Zero();  // from the centre to one end
    double radius_m = 0.0;
  };

 private:
  // A capsule's points on a box's faces (no sphere radius), rewritten: where some of its balls'
  // lifts have a crease under them (ballOnReliefContacts: a capsule lying along a V-groove), the
  // split balls at the two ends of their run get a point on each side of it (crease tags 1-4:
  // side + 2 slot), the split balls between them go, and the unsplit balls' points stay while the
  // manifold has room; their impulses from `before`. Elsewhere each point as
  // applyBallMeshContact rewrites it. false: not split here (the caller rewrites each point).
  bool splitCapsuleAtCreases(btPersistentManifold& manifold, const ObjectAxis& axis,
                             const Eigen::Isometry3d& world_from_object, const Eigen::Isometry3d& world_from_mesh,
                             const btCollisionObject& object, const StepContext& step, const CreaseSides& before);
  struct BallGroup {
    int code = 0;   // its place along the axis, as kept in its points
    int first = 0;  // its first point in the manifold
    ObjectBall ball;
    std::optional<BallContactsAtFoot> at;
  };
  std::vector<BallGroup> groups_;
  std::vector<BallGroup> ends_;  // the balls split at a crease that get a point on each side

  bool faces_first_;
  const ObjectFaces* faces_;
  std::vector<int> near_;  // the triangles within reach this step, in index order
  std::vector<std::pair<double, std::uint32_t>> trail_;  // on a ball: each sample's place on the run, its foot's triangle
  const ObjectFacesCatalog* catalog_;
};

}  // namespace thx::phys
