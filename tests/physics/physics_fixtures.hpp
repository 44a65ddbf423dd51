#pragma once
// Shared by the physics tests: textures with analytic geometry and small simulation helpers.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>

#include "clients/physics/physics_world.hpp"
#include "textures/generators.hpp"
#include "textures/height_normals.hpp"
#include "textures/textured_surface.hpp"

namespace thx::phys::test {

inline constexpr double kG = 9.81;
inline constexpr double kPi = std::numbers::pi;
inline double deg(double d) { return d * kPi / 180.0; }

// A texture map with a stable address plus the surface that reads it.
struct SurfaceHolder {
  std::unique_ptr<tex::TextureMap> map;
  tex::TexturedSurface surface;
};

inline SurfaceHolder holdSurface(tex::TextureMap map, double extent_m, bool relief,
                                 tex::Address address = tex::Address::Wrap,
                                 const Eigen::Isometry3d& plane_to_world = Eigen::Isometry3d::Identity()) {
  SurfaceHolder h;
  h.map = std::make_unique<tex::TextureMap>(std::move(map));
  tex::PlaneMapping mapping;
  mapping.size_m = {extent_m, extent_m};
  mapping.plane_to_world = plane_to_world;
  tex::SampleOptions sampling;
  sampling.address = address;
  h.surface = tex::TexturedSurface(*h.map, mapping, sampling, relief);
  return h;
}

// The generator's uniformly tilted plane: the normal leans angle_deg towards +x (downhill = +x).
inline tex::TextureMap tiltedMap(double angle_deg, int size, double extent_m) {
  tex::GenerateRequest r;
  r.kind = "tilted";
  r.size = size;
  r.params = {{"angle_deg", angle_deg}, {"direction_deg", 0.0}, {"extent", extent_m}};
  return tex::generate(r);
}

// A relief/normal map of an analytic height h(x, y) (m, +up, plane-local coordinates centred on
// the map), sampled at texel centres, normals by the texture library's central differences.
inline tex::TextureMap heightMap(int size, double extent_m, const std::function<double(double, double)>& h,
                                 tex::Address address = tex::Address::Wrap) {
  tex::HeightField field(size, size);
  const double d = extent_m / size;
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) field.at(i, j) = h((i + 0.5) * d - 0.5 * extent_m, 0.5 * extent_m - (j + 0.5) * d);
  tex::ReliefFromHeightOptions o;
  o.texel_m = {d, d};
  o.address = address;
  return tex::reliefFromHeight(field, o);
}

inline tex::TextureMap flatRelief(int size, double max_depth_m = 1e-3) {
  return tex::TextureMap(size, size, tex::Representation::Relief, max_depth_m);
}

// A world whose bodies never sleep (a test of creep must see every step), on one relief plane of
// the height h (extent_m across, `texels` a side) with friction 1, so that Bullet's product of the
// two frictions is the object's own.
struct ReliefWorld {
  SurfaceHolder relief;
  std::unique_ptr<PhysicsWorld> world;
  ReliefWorld(const std::function<double(double, double)>& h, double extent_m, int texels,
              tex::Address address = tex::Address::Clamp) {
    relief = holdSurface(heightMap(texels, extent_m, h, address), extent_m, true, address);
    WorldOptions options;
    options.rest.enabled = false;
    world = std::make_unique<PhysicsWorld>(options);
    world->addReliefPlane(relief.surface, {1.0, 0.0, 0.0});
  }
};

// The pose of an object standing on the plane through `foot` that rises along -x with `slope`, its
// own z axis along that plane's normal and its centre `half_height` (+ 10 µm) above `foot`, turned
// by `yaw` about its own z axis.
inline Eigen::Isometry3d onSlope(double slope, const Eigen::Vector3d& foot, double half_height, double yaw = 0.0) {
  const double angle = std::atan(slope);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() =
      (Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())).toRotationMatrix();
  pose.translation() = foot + (half_height + 1e-5) * Eigen::Vector3d(std::sin(angle), 0.0, std::cos(angle));
  return pose;
}

inline Eigen::Isometry3d at(double x, double y, double z) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(x, y, z);
  return t;
}

// Rounded U grooves along y (12.5 mm period, 8 mm wide, 1.5 mm deep), as in
// scenes/pen_pushes_ball.yaml: a 6 mm ball is wider than the groove's floor and rests on its
// two walls, two contacts pushing against each other.
inline double uGroove(double x, double) {
  const double pitch = 0.0125, half_width = 0.004, dep = 1.5e-3;
  const double dx = x - std::round(x / pitch) * pitch;
  return std::fabs(dx) < half_width ? -dep * std::cos(0.5 * kPi * dx / half_width) : 0.0;
}

// Rolling without slip along +x on a surface below: omega_y = v / r.
inline void setRolling(btRigidBody& ball, double v_x, double radius) {
  setVelocity(ball, {v_x, 0.0, 0.0}, {0.0, v_x / radius, 0.0});
}

}  // namespace thx::phys::test
