#pragma once
// The smooth surface under a chart (a textured mesh's tangent plane at a contact, issue 29), as
// its height above that plane: h = (xx dx^2 + 2 xy dx dy + yy dy^2) / 2 with (dx, dy) = (x, y) -
// centre, the second fundamental form at the point of the chart where it touches the surface. A relief laid on the chart stands on this bent ground rather than on
// the flat plane: on a 70 mm bowl's floor a 16 mm box's edges lie 0.46 mm above the tangent plane,
// more than a groove's depth. Zero everywhere for a plane.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace thx::phys {

struct GroundBend {
  double xx = 0.0, xy = 0.0, yy = 0.0;  // 1/m: curvatures along x, y and the twist
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // where the plane touches the ground
  // Whether the form was fitted to the ground around (mesh_relief_chart.cpp): not where too few
  // points were left to fit (on a sphere mesh smaller than the object's reach), where the ground
  // is curved though the form reads flat. A plane's is known.
  bool known = true;

  double height(double x, double y) const {
    x -= centre.x(), y -= centre.y();
    return 0.5 * (xx * x * x + 2.0 * xy * x * y + yy * y * y);
  }
  // The ground's slope (dh/dx, dh/dy).
  Eigen::Vector2d slope(double x, double y) const {
    x -= centre.x(), y -= centre.y();
    return {xx * x + xy * y, xy * x + yy * y};
  }
  // A relief normal n (plane frame, unit) laid on the bent ground at (x, y): its slopes plus the
  // ground's (n is -grad(height) scaled by n.z, so the ground's slope adds to it the same way).
  Eigen::Vector3d tilt(const Eigen::Vector3d& n, double x, double y) const {
    const Eigen::Vector2d s = slope(x, y);
    return Eigen::Vector3d(n.x() - s.x() * n.z(), n.y() - s.y() * n.z(), n.z()).normalized();
  }
  // An upper bound of the ground's height over a rectangle (>= 0): how far above the plane the
  // ground can rise under an object there.
  double highestOver(const Eigen::AlignedBox2d& box) const {
    const double ax = std::max(std::fabs(box.min().x() - centre.x()), std::fabs(box.max().x() - centre.x()));
    const double ay = std::max(std::fabs(box.min().y() - centre.y()), std::fabs(box.max().y() - centre.y()));
    return std::max(0.0, 0.5 * (std::max(xx, 0.0) * ax * ax + 2.0 * std::fabs(xy) * ax * ay + std::max(yy, 0.0) * ay * ay));
  }
  bool flat() const { return xx == 0.0 && xy == 0.0 && yy == 0.0; }
  // Whether the ground rises less than `tolerance` (m) within `reach` (m) of the centre: a flat
  // face's fit is rounding, 1e-15 /m on a box's face (mesh_relief_chart.cpp).
  bool flatWithin(double reach, double tolerance) const {
    return 0.5 * (std::fabs(xx) + 2.0 * std::fabs(xy) + std::fabs(yy)) * reach * reach <= tolerance;
  }
};

}  // namespace thx::phys
