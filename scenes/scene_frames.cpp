#include "scenes/scene_frames.hpp"

#include <numbers>

namespace thx::scene {

Eigen::Isometry3d toIsometry(const Pose& pose) {
  const Eigen::Vector3d rpy = pose.rpy_deg * (std::numbers::pi / 180.0);
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() =
      (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  t.translation() = pose.position_m;
  return t;
}

tex::PlaneMapping planeMapping(const Surface& surface) {
  tex::PlaneMapping mapping;
  mapping.size_m = surface.size_m;
  mapping.plane_to_world = toIsometry(surface.pose);
  return mapping;
}

}  // namespace thx::scene
