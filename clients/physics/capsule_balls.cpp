#include "clients/physics/capsule_balls.hpp"

#include <algorithm>
#include <cmath>

#include "meshes/textured_mesh.hpp"

namespace thx::phys {

void closestOnSegments(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                       const Eigen::Vector3d& d, double& s, double& u) {
  const Eigen::Vector3d d1 = b - a, d2 = d - c, r = a - c;
  const double A = d1.squaredNorm(), E = d2.squaredNorm(), F = d2.dot(r);
  constexpr double kTiny = 1e-30;
  const auto unit = [](double x) { return std::clamp(x, 0.0, 1.0); };
  s = 0.0;
  u = 0.0;
  if (A <= kTiny && E <= kTiny) return;
  if (A <= kTiny) {
    u = unit(F / E);
    return;
  }
  const double C = d1.dot(r);
  if (E <= kTiny) {
    s = unit(-C / A);
    return;
  }
  const double B = d1.dot(d2), denom = A * E - B * B;
  // Parallel segments: any point of the overlap is nearest; start from a.
  s = denom > kTiny * A * E ? unit((B * F - C * E) / denom) : 0.0;
  u = (B * s + F) / E;
  if (u < 0.0) {
    u = 0.0;
    s = unit(-C / A);
  } else if (u > 1.0) {
    u = 1.0;
    s = unit((B - C) / A);
  }
}

double distanceToTriangle(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                          const Eigen::Vector3d& p) {
  const Eigen::Vector3d w = mesh::closestBarycentric(p0, p1, p2, p);
  return (p - (w.x() * p0 + w.y() * p1 + w.z() * p2)).norm();
}

SegmentOverTriangle segmentOverTriangle(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                                        const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const std::array<Eigen::Vector3d, 3> p{p0, p1, p2};
  const Eigen::Vector3d face = (p1 - p0).cross(p2 - p0);
  const auto distance = [&](double t) { return distanceToTriangle(p0, p1, p2, Eigen::Vector3d(a + t * (b - a))); };

  // The run of the segment over the triangle: clipped by the three planes through its edges along
  // its normal (face x edge points inwards for either winding, as face follows the winding).
  SegmentOverTriangle over;
  double lo = 0.0, hi = 1.0;
  for (int k = 0; k < 3 && lo <= hi; ++k) {
    const Eigen::Vector3d inward = face.cross(p[std::size_t((k + 1) % 3)] - p[std::size_t(k)]);
    const double da = inward.dot(a - p[std::size_t(k)]), db = inward.dot(b - p[std::size_t(k)]);
    if (da < 0.0 && db < 0.0) {
      hi = -1.0;
    } else if (da < 0.0) {
      lo = std::max(lo, da / (da - db));
    } else if (db < 0.0) {
      hi = std::min(hi, da / (da - db));
    }
  }
  over.runs_over = lo <= hi;
  over.lo = lo;
  over.hi = hi;

  // The nearest point: the distance along a segment is convex; inside the run it is the distance
  // to the plane (least at an end of the run or where the segment crosses the plane), outside it
  // the distance to an edge, never below the least distance from the segment to that edge.
  std::array<double, 8> candidates{};
  int n = 0;
  candidates[std::size_t(n++)] = 0.0;
  candidates[std::size_t(n++)] = 1.0;
  if (over.runs_over) {
    candidates[std::size_t(n++)] = lo;
    candidates[std::size_t(n++)] = hi;
    const double ha = face.dot(a - p0), hb = face.dot(b - p0);
    if ((ha < 0.0) != (hb < 0.0)) candidates[std::size_t(n++)] = std::clamp(ha / (ha - hb), lo, hi);
  }
  for (int k = 0; k < 3; ++k) {
    double s = 0.0, u = 0.0;
    closestOnSegments(a, b, p[std::size_t(k)], p[std::size_t((k + 1) % 3)], s, u);
    candidates[std::size_t(n++)] = s;
  }
  double best = distance(candidates[0]);
  over.nearest_t = candidates[0];
  for (int k = 1; k < n; ++k) {
    const double d = distance(candidates[std::size_t(k)]);
    if (d < best) {
      best = d;
      over.nearest_t = candidates[std::size_t(k)];
    }
  }
  return over;
}

}  // namespace thx::phys
