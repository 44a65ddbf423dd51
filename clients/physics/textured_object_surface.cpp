#include "clients/physics/textured_object_surface.hpp"

#include "clients/physics/textured_ball.hpp"

namespace thx::phys {

TexturedObjectSurface::TexturedObjectSurface(const Underside& object, const FaceTexture& texture)
    : object_(object),
      texture_(texture),
      object_from_plane_(object.plane_from_object.inverse()),
      down_object_(-object.plane_from_object.linear().row(2).transpose()) {}

ObjectSurfacePoint TexturedObjectSurface::over(double x, double y, double lowest_z) const {
  const Eigen::Vector3d p = object_from_plane_ * Eigen::Vector3d(x, y, lowest_z);
  if (object_.kind != Underside::Kind::Sphere) {
    const BoxPoint box = boxAt(p, lowest_z);
    return {box.z, boxNormalUp(box)};
  }
  const FacePoint relief = ballTextureAt(texture_, object_.radius, p);
  // The smooth surface's outward normal against the plane's -z.
  const double down = p.normalized().dot(down_object_);
  if (down <= kSteepestTexturedFaceCos) return {lowest_z, std::nullopt};
  return {lowest_z + relief.recess_m / down, Eigen::Vector3d(-(object_.plane_from_object.linear() * relief.normal_object))};
}

TexturedObjectSurface::BoxPoint TexturedObjectSurface::boxAt(const Eigen::Vector3d& p, double lowest_z) const {
  BoxPoint b{lowest_z, false, faceSampleAt(texture_, object_.half_extents, p, down_object_)};
  const double down = faceDown(b.sample.face);
  b.steep = down <= kSteepestTexturedFaceCos;
  if (!b.steep) b.z = lowest_z + b.sample.face.recess_m / down;
  return b;
}

std::optional<Eigen::Vector3d> TexturedObjectSurface::boxNormalUp(const BoxPoint& p) const {
  if (p.steep) return std::nullopt;
  return Eigen::Vector3d(-(object_.plane_from_object.linear() * faceNormal(p.sample)));
}

double TexturedObjectSurface::faceDown(const FacePoint& face) const {
  return -face.sign * object_.plane_from_object.linear()(2, face.axis);
}

double TexturedObjectSurface::zOver(double x, double y, double lowest_z) const {
  if (object_.kind != Underside::Kind::Sphere) return boxAt(object_from_plane_ * Eigen::Vector3d(x, y, lowest_z), lowest_z).z;
  const Eigen::Vector3d w = (object_from_plane_ * Eigen::Vector3d(x, y, lowest_z)).normalized();
  const double down = w.dot(down_object_);
  if (down <= kSteepestTexturedFaceCos) return lowest_z;
  return lowest_z + ballRecessAtUnit(texture_, object_.radius, w) / down;
}

std::optional<ObjectSurfacePoint> TexturedObjectSurface::at(double x, double y) const {
  const std::optional<double> z = lowestZ(object_, x, y);
  if (!z) return std::nullopt;
  return over(x, y, *z);
}

}  // namespace thx::phys
