#pragma once
// A perspective camera orbiting a target point: elevation above the plane, azimuth around the
// plane's normal, distance. Matrices are OpenGL's (column-major, clip z in [-1, 1]); the CPU
// references use pixelRay() so they see exactly the rays the rasteriser samples (pixel centres).
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace thx::visual {

struct CameraPlacement {
  double elevation_deg = 35.0;  // 90 = straight down onto the plane
  double azimuth_deg = -90.0;   // where the eye stands seen from the target: -90 = towards -y
  double distance_m = 0.25;
  Eigen::Vector2d target_local{0.0, 0.0};  // on the plane, surface-local metres
  double fov_y_deg = 40.0;
};

struct Ray {
  Eigen::Vector3d origin;
  Eigen::Vector3d direction;  // unit
};

class Camera {
 public:
  // `plane_to_world` orients the orbit: elevation and azimuth are measured in the plane's frame.
  Camera(const CameraPlacement& placement, const Eigen::Isometry3d& plane_to_world, int width, int height);

  const Eigen::Matrix4d& view() const { return view_; }
  const Eigen::Matrix4d& projection() const { return projection_; }
  Eigen::Matrix4d viewProjection() const { return projection_ * view_; }
  const Eigen::Vector3d& eyeWorld() const { return eye_world_; }
  // The world ray through the centre of pixel (x, y), (0, 0) = the image's top-left pixel.
  Ray pixelRay(int x, int y) const;

 private:
  int width_, height_;
  Eigen::Vector3d eye_world_;
  Eigen::Matrix4d view_, projection_, inverse_view_projection_;
};

}  // namespace thx::visual
