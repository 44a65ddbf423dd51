#include "clients/physics/textured_box_rows.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thx::phys {

TexturedBoxRows::TexturedBoxRows(const Underside& box, const TexturedObjectSurface& surface)
    : surface_(surface), centre_(box.plane_from_object.translation()) {
  const Eigen::Matrix3d& r = box.plane_from_object.linear();
  for (int k = 0; k < 3; ++k) {
    axes_[std::size_t(k)] = r.col(k);
    half_[std::size_t(k)] = box.half_extents[k];
    parallel_[std::size_t(k)] = std::fabs(r(2, k)) < kParallelSine;
    inv_sine_[std::size_t(k)] = parallel_[std::size_t(k)] ? 0.0 : 1.0 / r(2, k);
  }
}

void TexturedBoxRows::startRow(double y) {
  for (std::size_t k = 0; k < 3; ++k) row_part_[k] = (y - centre_.y()) * axes_[k].y() - centre_.z() * axes_[k].z();
}

bool TexturedBoxRows::at(double x, Point& out) const {
  // The vertical line through (x, y) inside each slab |s_k + t sine_k| <= h_k (s_k: its slab
  // coordinate at z = 0), as lowestZ's slabInterval.
  constexpr double kUnbounded = std::numeric_limits<double>::infinity();
  std::array<double, 3> s{};
  double lo = -kUnbounded, hi = kUnbounded;
  for (std::size_t k = 0; k < 3; ++k) {
    s[k] = (x - centre_.x()) * axes_[k].x() + row_part_[k];
    if (parallel_[k]) {
      if (std::fabs(s[k]) > half_[k]) return false;
      continue;
    }
    const double t1 = (-half_[k] - s[k]) * inv_sine_[k], t2 = (half_[k] - s[k]) * inv_sine_[k];
    lo = std::max(lo, std::min(t1, t2));
    hi = std::min(hi, std::max(t1, t2));
  }
  if (lo > hi || !std::isfinite(lo)) return false;
  out.lowest_z = lo;
  // The point's object coordinates: its slab coordinates at that height.
  Eigen::Vector3d p;
  for (std::size_t k = 0; k < 3; ++k) p[Eigen::Index(k)] = s[k] + lo * axes_[k].z();
  out.surface = surface_.boxAt(p, lo);
  return true;
}

}  // namespace thx::phys
