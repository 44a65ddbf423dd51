#pragma once
// From scene poses to transforms: the rpy convention lives here and nowhere else.
//   R = Rz(yaw) * Ry(pitch) * Rx(roll), rpy_deg = [roll, pitch, yaw] in degrees.
#include <Eigen/Geometry>

#include "scenes/scene.hpp"
#include "textures/plane_mapping.hpp"

namespace thx::scene {

Eigen::Isometry3d toIsometry(const Pose& pose);

// The surface rectangle in the world, ready for (x, y) <-> (u, v) mapping.
tex::PlaneMapping planeMapping(const Surface& surface);

}  // namespace thx::scene
