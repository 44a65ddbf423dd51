#include "clients/physics_client/mesh_ground.hpp"

#include <cmath>
#include <utility>

#include "textures/height_from_normals.hpp"

namespace thx::physclient {

namespace {

phys::MeshContactOptions contactOptionsFor(const tex::TexturedSurface& texture, const tex::TextureMap& contact_map,
                                           const tex::BallOnRelief* ball_relief, const Eigen::Vector2d& mean_slope) {
  phys::MeshContactOptions o;
  o.texture = &contact_map;
  o.ball_relief = ball_relief;
  o.relief_mean_slope = mean_slope;
  o.sampling = texture.sampling();
  o.normals_made_for_m = texture.mapping().size_m;  // the scene's tile (surface.size), as hapticd's
  return o;
}

}  // namespace

MeshGround::MeshGround(const scene::Scene& scene, const tex::TexturedSurface& texture)
    : texture_(&texture), scene_mesh_(scene::buildSceneMesh(scene)), contact_mesh_(scene_mesh_.mesh) {
  const tex::TextureMap& map = texture.map();
  const tex::Address address = texture.sampling().address;
  if (map.maxDepth() > 0.0) {
    ball_relief_.emplace(map, address);
    options_ = contactOptionsFor(texture, map, &*ball_relief_, Eigen::Vector2d::Zero());
    return;
  }
  // Made for the scene's tile (surface.size).
  tex::ReliefOfNormals integrated =
      tex::reliefFromNormals(map, texture.mapping().size_m, address, "the relief of the scene's normal map");
  relief_ = std::move(integrated.relief);
  mean_slope_ = integrated.mean_slope;
  ball_relief_.emplace(*relief_, address);
  // Every body meets the relief; leaning, its contacts' normals tilted by the mean slope (a ball's
  // lift, the chart's points of the others).
  const bool level = mean_slope_.norm() <= kLevelSlope;
  options_ = contactOptionsFor(texture, *relief_, &*ball_relief_, level ? Eigen::Vector2d::Zero() : mean_slope_);
}

btRigidBody& MeshGround::addTo(phys::PhysicsWorld& world, const phys::BodyMaterial& material) const {
  return world.addTexturedMesh(scene_mesh_.mesh, scene_mesh_.mesh_to_world, material, options_);
}

MeshGround::Place MeshGround::placeAt(std::uint32_t triangle, const Eigen::Vector3d& b) const {
  const mesh::SurfaceFrame f = mesh::frameAt(scene_mesh_.mesh, triangle, b, mesh::FrameMode::Interpolated);
  Place p;
  p.triangle = triangle;
  p.barycentric = b;
  p.p_world = scene_mesh_.mesh_to_world * f.point;
  p.uv = {f.uv.x(), f.uv.y()};
  p.metres_per_uv = mesh::metresPerUv(scene_mesh_.mesh, triangle, f);
  return p;
}

MeshGround::Place MeshGround::on(std::uint32_t triangle, const Eigen::Vector3d& p_world) const {
  const Eigen::Vector3d p = scene_mesh_.mesh_to_world.inverse() * p_world;
  return placeAt(triangle, mesh::closestBarycentric(scene_mesh_.mesh, triangle, p));
}

MeshGround::Place MeshGround::footOf(const Eigen::Vector3d& c_world, std::uint32_t near) const {
  const mesh::TexturedMesh& m = scene_mesh_.mesh;
  const Eigen::Vector3d c = scene_mesh_.mesh_to_world.inverse() * c_world;
  Eigen::Vector3d b = mesh::closestBarycentric(m, near, c);
  const mesh::SurfaceFrame f = mesh::frameAt(m, near, b, mesh::FrameMode::Interpolated);
  const double side = f.normal.dot(c - f.point) < 0.0 ? -1.0 : 1.0;  // -1: behind the winding (a bowl's inside)
  std::uint32_t triangle = near;
  phys::smoothFoot(contact_mesh_, c, side, triangle, b);
  return placeAt(triangle, b);
}

void MeshGround::texelOf(const tex::TexCoord& uv, long long& i, long long& j) const {
  const tex::TextureMap& map = texture_->map();
  i = tex::TexturedSurface::toIndex(uv.u * map.width());
  j = tex::TexturedSurface::toIndex((1.0 - uv.v) * map.height());
}

Eigen::Vector3d MeshGround::texelNormalWorld(long long i, long long j, const Place& at) const {
  const tex::TextureMap& map = texture_->map();
  const int ri = tex::resolveIndex(i, map.width(), texture_->sampling().address);
  const int rj = tex::resolveIndex(j, map.height(), texture_->sampling().address);
  const mesh::SurfaceFrame f = mesh::frameAt(scene_mesh_.mesh, at.triangle, at.barycentric, mesh::FrameMode::Interpolated);
  const Eigen::Vector3d n =
      phys::meshTextureNormal(scene_mesh_.mesh, at.triangle, f, map.normal(ri, rj).cast<double>(), options_);
  return scene_mesh_.mesh_to_world.linear() * n;
}

}  // namespace thx::physclient
