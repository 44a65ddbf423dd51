#include "clients/visual/camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace thx::visual {
namespace {

double radians(double deg) { return deg * std::numbers::pi / 180.0; }

Eigen::Matrix4d lookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target, const Eigen::Vector3d& up_hint) {
  const Eigen::Vector3d f = (target - eye).normalized();
  Eigen::Vector3d s = f.cross(up_hint);
  if (s.norm() < 1e-9) s = f.unitOrthogonal();  // looking straight along the hint
  s.normalize();
  const Eigen::Vector3d u = s.cross(f);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m;
}

Eigen::Matrix4d perspective(double fov_y_deg, double aspect, double near_m, double far_m) {
  const double t = 1.0 / std::tan(radians(fov_y_deg) / 2);
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = t / aspect;
  p(1, 1) = t;
  p(2, 2) = (far_m + near_m) / (near_m - far_m);
  p(2, 3) = 2 * far_m * near_m / (near_m - far_m);
  p(3, 2) = -1;
  return p;
}

}  // namespace

Camera::Camera(const CameraPlacement& c, const Eigen::Isometry3d& plane_to_world, int width, int height)
    : width_(width), height_(height) {
  const double el = radians(c.elevation_deg), az = radians(c.azimuth_deg);
  const Eigen::Vector3d offset_local(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
  const Eigen::Vector3d target_world = plane_to_world * Eigen::Vector3d(c.target_local.x(), c.target_local.y(), 0.0);
  eye_world_ = target_world + plane_to_world.linear() * (offset_local * c.distance_m);
  // Up on screen: the plane's normal, or its +y when looking straight down.
  const Eigen::Vector3d normal = plane_to_world.linear().col(2);
  const Eigen::Vector3d up = c.elevation_deg > 89.9 ? Eigen::Vector3d(plane_to_world.linear().col(1)) : normal;
  view_ = lookAt(eye_world_, target_world, up);
  projection_ = perspective(c.fov_y_deg, double(width) / height, c.distance_m * 0.02, c.distance_m * 20.0);
  inverse_view_projection_ = (projection_ * view_).inverse();
}

Ray Camera::pixelRay(int x, int y) const {
  const double nx = (x + 0.5) / width_ * 2.0 - 1.0;
  const double ny = 1.0 - (y + 0.5) / height_ * 2.0;
  const Eigen::Vector4d near_h = inverse_view_projection_ * Eigen::Vector4d(nx, ny, -1.0, 1.0);
  const Eigen::Vector4d far_h = inverse_view_projection_ * Eigen::Vector4d(nx, ny, 1.0, 1.0);
  const Eigen::Vector3d a = near_h.head<3>() / near_h.w(), b = far_h.head<3>() / far_h.w();
  return {a, (b - a).normalized()};
}

}  // namespace thx::visual
