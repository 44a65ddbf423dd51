#pragma once
// Where a texture lies in the world: a rectangle of size (size_x, size_y) metres, centred on the
// origin of its own frame, with the plane's geometric normal along local +z. `plane_to_world`
// places that frame in the world.
//
//   local (x, y)  <->  (u, v):  u = x / size_x + 0.5,  v = y / size_y + 0.5
//
// so the texture spans the rectangle once; (u, v) outside [0,1) continues by the texture's
// address mode (wrap repeats it, clamp extends its edges).
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "textures/sampling.hpp"

namespace thx::tex {

struct PlaneMapping {
  Eigen::Vector2d size_m{0.2, 0.2};
  Eigen::Isometry3d plane_to_world = Eigen::Isometry3d::Identity();

  TexCoord uvOfLocal(const Eigen::Vector2d& xy_local) const {
    return {xy_local.x() / size_m.x() + 0.5, xy_local.y() / size_m.y() + 0.5};
  }
  Eigen::Vector2d localOfUv(TexCoord uv) const {
    return {(uv.u - 0.5) * size_m.x(), (uv.v - 0.5) * size_m.y()};
  }
  Eigen::Vector3d toLocal(const Eigen::Vector3d& p_world) const { return plane_to_world.inverse() * p_world; }
  Eigen::Vector3d toWorld(const Eigen::Vector3d& p_local) const { return plane_to_world * p_local; }
  // Tangent-frame (= plane-local) direction to world.
  Eigen::Vector3d directionToWorld(const Eigen::Vector3d& d_local) const { return plane_to_world.linear() * d_local; }
  Eigen::Vector3d directionToLocal(const Eigen::Vector3d& d_world) const {
    return plane_to_world.linear().transpose() * d_world;
  }
  Eigen::Vector3d geometricNormalWorld() const { return plane_to_world.linear().col(2); }
  // Texel size in metres along x and y for a map of the given resolution.
  Eigen::Vector2d texelSize(const TextureMap& map) const {
    return {size_m.x() / map.width(), size_m.y() / map.height()};
  }
};

}  // namespace thx::tex
