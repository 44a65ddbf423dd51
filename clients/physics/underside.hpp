#pragma once
// The underside of a convex object seen from the textured plane: for a vertical line through
// plane-local (x, y), the lowest z of the object on it (where a ray going up from below the
// plane enters the object). Relief contact rasterises this over the object's footprint texels.
// Pure geometry in double, in the PLANE frame (z = the plane's normal); no Bullet types.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <optional>

namespace thx::phys {

struct Underside {
  enum class Kind { Sphere, Box, Capsule, Cylinder };
  Kind kind = Kind::Sphere;
  Eigen::Isometry3d plane_from_object = Eigen::Isometry3d::Identity();  // object frame -> plane frame
  Eigen::Vector3d half_extents = Eigen::Vector3d::Zero();  // box: half edge lengths
  double radius = 0.0;       // sphere, capsule, cylinder
  double half_length = 0.0;  // capsule: half the distance between cap centres; cylinder: half height
  int axis = 2;              // capsule, cylinder: the object-frame axis they extend along

  static Underside sphere(const Eigen::Isometry3d& pose, double radius);
  static Underside box(const Eigen::Isometry3d& pose, const Eigen::Vector3d& half_extents);
  static Underside capsule(const Eigen::Isometry3d& pose, double radius, double half_length, int axis = 2);
  static Underside cylinder(const Eigen::Isometry3d& pose, double radius, double half_length, int axis = 2);
};

// Which of a box's axes (columns of `axes`, the box in the plane's frame) lies most along the
// plane's normal: its other two lie most in the plane.
inline int mostUprightAxis(const Eigen::Matrix3d& axes) {
  int down = 0;
  for (int k = 1; k < 3; ++k) down = std::fabs(axes(2, k)) > std::fabs(axes(2, down)) ? k : down;
  return down;
}

// Below this |sin| a vertical line counts as parallel to a face or slab of the object (no z bound).
inline constexpr double kParallelSine = 1e-12;

// Lowest z of the object on the vertical line through (x, y); nullopt if the line misses it.
std::optional<double> lowestZ(const Underside& shape, double x, double y);

// lowestZ of a sphere of radius r centred at c (plane frame), to the bit: inline for the rasters,
// which ask it at every texel under a ball (a third of a bump-mapped ball's collision time went
// to the call and its copy of the pose's rotation, which a sphere does not need; 2026-12-05).
inline std::optional<double> sphereLowestZ(const Eigen::Vector3d& c, double r, double x, double y) {
  const double dx = x - c.x(), dy = y - c.y();
  const double h2 = r * r - dx * dx - dy * dy;
  if (h2 < 0.0) return std::nullopt;
  const double lo = c.z() - std::sqrt(h2);
  if (!std::isfinite(lo)) return std::nullopt;
  return lo;
}

// Where a contact with surface normal n (plane frame, unit, pointing out of the relief) acts on
// the object, given the object's lowest point p above a texel. On round parts the point moves to
// where the object's own surface normal is -n (Eq. 2 generalised): a sphere's q = c - r n, a
// capsule's or a cylinder side's axis point minus r times n's component across the axis. The
// push then passes through the centre / axis, so a discrete texel offset cannot spin the body.
// Flat parts (box, cylinder end faces) keep p.
Eigen::Vector3d contactOnObject(const Underside& shape, const Eigen::Vector3d& p_lowest, const Eigen::Vector3d& n);

// A box's lower face that the vertical line through (x, y) enters by: its axis (0-2) times 2,
// plus 1 where it is the face at +half extent; -1 where the line misses the box.
int boxFaceUnder(const Underside& box, double x, double y);
// That face's normal pointing up, out of the relief into the box (plane frame).
Eigen::Vector3d boxFaceNormalUp(const Underside& box, int face);

// Exact axis-aligned bounds of the object in the plane frame (its footprint is the xy part).
Eigen::AlignedBox3d planeBounds(const Underside& shape);

}  // namespace thx::phys
