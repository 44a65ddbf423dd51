#include "benchmarks/mesh_closest.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thx::bench {

namespace {
Eigen::Vector3d closestOnSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  return a + std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) * ab;
}
}  // namespace

Eigen::Vector3d closestOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                  const Eigen::Vector3d& c) {
  // The foot of p on the plane, if it lies inside (on the inner side of every edge); else the
  // nearest of the three edges' closest points.
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const Eigen::Vector3d foot = p - ((p - a).dot(n) / n.squaredNorm()) * n;
  const bool inside = (b - a).cross(foot - a).dot(n) >= 0 && (c - b).cross(foot - b).dot(n) >= 0 &&
                      (a - c).cross(foot - c).dot(n) >= 0;
  if (inside) return foot;
  Eigen::Vector3d best = closestOnSegment(p, a, b);
  for (const Eigen::Vector3d& q : {closestOnSegment(p, b, c), closestOnSegment(p, c, a)}) {
    if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
  }
  return best;
}

GridMeshReference::GridMeshReference(const srv::TriangleMesh& mesh, int n, const Eigen::Vector2d& size_m)
    : mesh_(&mesh), n_(n), size_(size_m), cell_(size_m / n) {}

double GridMeshReference::heightAt(double x, double y) const {
  const double fx = (x / size_.x() + 0.5) * n_, fy = (y / size_.y() + 0.5) * n_;
  const int c = std::clamp(int(std::floor(fx)), 0, n_ - 1), r = std::clamp(int(std::floor(fy)), 0, n_ - 1);
  const double s = fx - c, t = fy - r;  // in the quad; its diagonal runs from (r, c) to (r + 1, c + 1)
  const double z00 = vertex(r, c).z(), z11 = vertex(r + 1, c + 1).z();
  if (s >= t) return z00 + s * (vertex(r, c + 1).z() - z00) + t * (z11 - vertex(r, c + 1).z());
  return z00 + t * (vertex(r + 1, c).z() - z00) + s * (z11 - vertex(r + 1, c).z());
}

Eigen::Vector3d GridMeshReference::force(const Eigen::Vector3d& p, double k) const {
  const double below = heightAt(p.x(), p.y()) - p.z();
  if (!(below > 0)) return Eigen::Vector3d::Zero();
  // The closest point is no farther than the mesh straight above: only cells within that reach.
  const auto index = [&](double v, double size, double cell) { return (v + size / 2) / cell; };
  const int c0 = std::max(0, int(std::floor(index(p.x() - below, size_.x(), cell_.x()))));
  const int c1 = std::min(n_ - 1, int(std::floor(index(p.x() + below, size_.x(), cell_.x()))));
  const int r0 = std::max(0, int(std::floor(index(p.y() - below, size_.y(), cell_.y()))));
  const int r1 = std::min(n_ - 1, int(std::floor(index(p.y() + below, size_.y(), cell_.y()))));
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d q = p;
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      for (const Eigen::Vector3d& x : {closestOnTriangle(p, vertex(r, c), vertex(r, c + 1), vertex(r + 1, c + 1)),
                                       closestOnTriangle(p, vertex(r, c), vertex(r + 1, c + 1), vertex(r + 1, c))}) {
        const double d = (x - p).squaredNorm();
        if (d < best) {
          best = d;
          q = x;
        }
      }
    }
  }
  return k * (q - p);
}

}  // namespace thx::bench
