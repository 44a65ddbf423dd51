#pragma once
// A textured object's surface as a mesh (issue 29): a box's six faces (meshes/textured_box_mesh.hpp)
// or a ball with a bump map's cube-sphere (meshes/textured_ball_mesh.hpp), laid as its texture is
// read, with what the contacts walk on and a Bullet BVH of its triangles. Another object meets it
// on the chart under it (box_ground.hpp, relief_collision.hpp: MeshRelief), a plain ball or a
// capsule as its triangles (ball_on_object_faces.hpp). Built once per textured object
// (ObjectFacesCatalog): the 6,912-triangle cube-sphere takes about 9 ms.
#include <BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h>

#include <Eigen/Core>
#include <memory>

#include "clients/physics/bullet_triangles.hpp"
#include "clients/physics/mesh_relief_chart.hpp"
#include "clients/physics/textured_box.hpp"
#include "meshes/textured_mesh.hpp"

namespace thx::phys {

class ObjectGround {
 public:
  // `texture` (nullptr: a plain surface, its smooth chart) must outlive this.
  ObjectGround(mesh::TexturedMesh surface, const FaceTexture* texture);
  ObjectGround(const ObjectGround&) = delete;
  ObjectGround& operator=(const ObjectGround&) = delete;

  const mesh::TexturedMesh& mesh() const { return mesh_; }
  const MeshRelief& relief() const { return *relief_; }
  // The faces as Bullet's triangles (the chart's boundary, chart_boundary.hpp; the triangles within
  // an object's reach); never in a world.
  const btConcaveShape& triangles() const { return *shape_; }

 private:
  mesh::TexturedMesh mesh_;
  std::unique_ptr<MeshRelief> relief_;  // reads mesh_
  std::unique_ptr<BulletTriangles> triangles_;
  std::unique_ptr<btBvhTriangleMeshShape> shape_;  // reads triangles_
};

// A box's: `half_extents_m` the whole box's (with Bullet's margin), `texture` nullptr for a plain box.
std::unique_ptr<ObjectGround> boxGround(const Eigen::Vector3d& half_extents_m, const FaceTexture* texture);
// A ball with a bump map's, `cells` quads along each face's edge (its Phong surface within 0.8 um of
// the sphere at 24 cells and 1 cm: docs/physics.md).
std::unique_ptr<ObjectGround> ballGround(double radius_m, const FaceTexture& texture, int cells = 24);

}  // namespace thx::phys
