#include "clients/physics/object_ground.hpp"

#include <utility>

#include "meshes/textured_ball_mesh.hpp"
#include "meshes/textured_box_mesh.hpp"

namespace thx::phys {

ObjectGround::ObjectGround(mesh::TexturedMesh surface, const FaceTexture* texture) : mesh_(std::move(surface)) {
  relief_ = std::make_unique<MeshRelief>(mesh_);
  if (texture) {
    relief_->map = texture->map;
    relief_->sampling = texture->sampling;
    // The relief is laid at the scale it was made for: one tile across tile_m.
    relief_->normals_made_for_m = Eigen::Vector2d::Constant(texture->tile_m);
  }
  triangles_ = bulletTriangles(mesh_);
  shape_ = std::make_unique<btBvhTriangleMeshShape>(triangles_->array.get(), true);
}

std::unique_ptr<ObjectGround> boxGround(const Eigen::Vector3d& half_extents_m, const FaceTexture* texture) {
  // A plain box's uv is never read (its chart is the smooth one): any tile will do.
  return std::make_unique<ObjectGround>(
      mesh::texturedBoxMesh(2.0 * half_extents_m, texture ? texture->tile_m : 2.0 * half_extents_m.maxCoeff()), texture);
}

std::unique_ptr<ObjectGround> ballGround(double radius_m, const FaceTexture& texture, int cells) {
  return std::make_unique<ObjectGround>(mesh::texturedBallMesh(radius_m, texture.tile_m, cells), &texture);
}

}  // namespace thx::phys
