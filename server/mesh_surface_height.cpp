#include "server/mesh_surface_height.hpp"

#include <algorithm>
#include <limits>

#include "base/error.hpp"

namespace thx::srv {

MeshSurfaceHeight::MeshSurfaceHeight(const TriangleBvh& bvh, const Eigen::Isometry3d& mesh_to_script) : bvh_(&bvh) {
  if (!mesh_to_script.matrix().allFinite() ||
      !(mesh_to_script.linear().transpose() * mesh_to_script.linear()).isIdentity(1e-9)) {
    throw thx::Error(thx::Error::Kind::Config,
                     "MeshSurfaceHeight: mesh_to_script is not a rigid transform; expected a finite rotation and "
                     "translation");
  }
  script_to_mesh_ = mesh_to_script.inverse(Eigen::Isometry);
  top_m_ = -std::numeric_limits<double>::infinity();
  bottom_m_ = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& v : bvh.vertices()) {  // the hierarchy's mesh has at least one triangle
    const double z = (mesh_to_script * v).z();
    top_m_ = std::max(top_m_, z);
    bottom_m_ = std::min(bottom_m_, z);
  }
}

bool MeshSurfaceHeight::heightAt(const Eigen::Vector2d& xy_m, double& z_m) const {
  const double z_from = top_m_ + kMarginM, z_to = bottom_m_ - kMarginM;
  const Eigen::Vector3d a = script_to_mesh_ * Eigen::Vector3d(xy_m.x(), xy_m.y(), z_from);
  const Eigen::Vector3d b = script_to_mesh_ * Eigen::Vector3d(xy_m.x(), xy_m.y(), z_to);
  const TriangleBvh::Hit hit = bvh_->firstEntry(a, b);  // false for a non-finite point too
  if (!hit.hit) return false;
  z_m = z_from + hit.t * (z_to - z_from);
  return true;
}

}  // namespace thx::srv
