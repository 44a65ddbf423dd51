#include "server/triangle_bvh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "meshes/textured_mesh.hpp"

#include "base/error.hpp"

namespace thx::srv {

namespace {
// Boxes grow by this fraction of their extent (plus an absolute floor) so that a point the
// barycentric tolerance accepts is never outside its leaf's box.
constexpr double kBoxPadRel = 1e-6;
constexpr double kBoxPadAbs = 1e-12;  // metres

// A mesh the hierarchy cannot be built on (it comes from a scene's textured mesh).
thx::Error meshError(const std::string& what) { return thx::Error(thx::Error::Kind::Config, "TriangleBvh: " + what); }
}  // namespace

TriangleBvh::TriangleBvh(const TriangleMesh& mesh, int leaf_size) : TriangleBvh(mesh.vertices, mesh.triangles, leaf_size) {}

TriangleBvh::TriangleBvh(const std::vector<Eigen::Vector3d>& vertices,
                         const std::vector<std::array<std::uint32_t, 3>>& triangles, int leaf_size)
    : vertices_(&vertices), triangles_(&triangles), leaf_size_(std::max(1, leaf_size)) {
  const std::size_t n = triangles.size();
  if (n == 0) throw meshError("the mesh has no triangles");
  if (n >= std::numeric_limits<std::uint32_t>::max() / 2) throw meshError("too many triangles");
  planes_.resize(n);
  std::vector<Eigen::Vector3d> centroids(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& tri = triangles[i];
    for (std::uint32_t v : tri) {
      if (v >= vertices.size()) {
        throw meshError("triangle " + std::to_string(i) + " uses vertex " + std::to_string(v) + " of " +
                        std::to_string(vertices.size()));
      }
    }
    const Eigen::Vector3d& p0 = vertices[tri[0]];
    const Eigen::Vector3d& p1 = vertices[tri[1]];
    const Eigen::Vector3d& p2 = vertices[tri[2]];
    const Eigen::Vector3d cross = (p1 - p0).cross(p2 - p0);
    const double len = cross.norm();
    const double scale = std::max({(p1 - p0).squaredNorm(), (p2 - p0).squaredNorm(), (p2 - p1).squaredNorm()});
    if (!(len > 1e-12 * scale) || !std::isfinite(len)) {
      throw meshError("triangle " + std::to_string(i) + " is degenerate (zero area)");
    }
    planes_[i].n = cross / len;
    planes_[i].d = planes_[i].n.dot(p0);
    centroids[i] = (p0 + p1 + p2) / 3.0;
  }
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), std::uint32_t{0});
  nodes_.reserve(2 * (n / std::size_t(leaf_size_) + 1));
  build(centroids, 0, std::uint32_t(n), 0);
}

std::uint32_t TriangleBvh::build(std::vector<Eigen::Vector3d>& centroids, std::uint32_t begin, std::uint32_t end,
                                 int depth) {
  if (depth > kMaxDepth) throw std::logic_error("TriangleBvh: hierarchy deeper than kMaxDepth");
  depth_ = std::max(depth_, depth);
  const std::uint32_t index = std::uint32_t(nodes_.size());
  nodes_.emplace_back();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo, c_lo = lo, c_hi = hi;
  for (std::uint32_t k = begin; k < end; ++k) {
    for (std::uint32_t v : (*triangles_)[order_[k]]) {
      lo = lo.cwiseMin((*vertices_)[v]);
      hi = hi.cwiseMax((*vertices_)[v]);
    }
    c_lo = c_lo.cwiseMin(centroids[order_[k]]);
    c_hi = c_hi.cwiseMax(centroids[order_[k]]);
  }
  const double pad = kBoxPadRel * (hi - lo).maxCoeff() + kBoxPadAbs;
  for (int k = 0; k < 3; ++k) {
    nodes_[index].lo[std::size_t(k)] = lo[k] - pad;
    nodes_[index].hi[std::size_t(k)] = hi[k] + pad;
  }
  if (end - begin <= std::uint32_t(leaf_size_)) {
    nodes_[index].first_or_right = begin;
    nodes_[index].count = end - begin;
    return index;
  }
  // Median split on the longest axis of the centroids: balanced, so the depth is log2(n / leaf).
  int axis = 0;
  (c_hi - c_lo).maxCoeff(&axis);
  const std::uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](std::uint32_t x, std::uint32_t y) { return centroids[x][axis] < centroids[y][axis]; });
  build(centroids, begin, mid, depth + 1);
  const std::uint32_t right = build(centroids, mid, end, depth + 1);
  nodes_[index].first_or_right = right;
  nodes_[index].count = 0;
  return index;
}

std::size_t TriangleBvh::bytes() const {
  return nodes_.size() * sizeof(Node) + order_.size() * sizeof(order_[0]) + planes_.size() * sizeof(planes_[0]);
}

SweepSegment sweepSegment(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  SweepSegment s;
  s.a = a;
  for (int k = 0; k < 3; ++k) {
    const double d = b[k] - a[k];
    s.parallel[std::size_t(k)] = d == 0.0;
    s.inv_d[k] = d == 0.0 ? 0.0 : 1.0 / d;
  }
  return s;
}

double TriangleBvh::typicalLeafExtent() const {
  std::vector<double> extents;
  for (const Node& node : nodes_) {
    if (node.count == 0) continue;
    double e = 0.0;
    for (std::size_t k = 0; k < 3; ++k) e = std::max(e, node.hi[k] - node.lo[k]);
    extents.push_back(e);
  }
  std::nth_element(extents.begin(), extents.begin() + std::ptrdiff_t(extents.size() / 2), extents.end());
  return extents[extents.size() / 2];
}

bool TriangleBvh::entersTriangleBy(std::uint32_t triangle, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   double t_max, double& t) const {
  double s = 0.0;
  // The corners are read only past the plane's test.
  if (!crossesFront(planes_[triangle], a, b, t_max, s) || !insideAt(entryCorners(triangle), a, b, s)) return false;
  t = s;
  return true;
}
bool TriangleBvh::enterLeaf(std::uint32_t first, std::uint32_t count, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const std::uint32_t* skip, int n_skip, Best& best) const {
  bool changed = false;
  for (std::uint32_t k = first; k < first + count; ++k) {
    const std::uint32_t tri = order_[k];
    double t = 0.0;
    if (skipped(skip, n_skip, tri) || !entersTriangleBy(tri, a, b, best.t, t)) continue;
    changed = keepIfFirst(best, t, tri) || changed;
  }
  return changed;
}

TriangleBvh::Hit TriangleBvh::hitOf(const Best& best, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  Hit hit;
  if (best.t <= 1.0) {
    hit.hit = true;
    hit.t = best.t;
    hit.triangle = best.triangle;
    hit.point = a + best.t * (b - a);
  }
  return hit;
}

TriangleBvh::Hit TriangleBvh::firstEntry(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const std::uint32_t* skip,
                                         int n_skip) const {
  if (!a.allFinite() || !b.allFinite()) return Hit{};
  const SweepSegment seg = sweepSegment(a, b);
  Best best;
  // Entry parameter kept with each node, so a node farther than a hit found meanwhile is dropped.
  std::array<std::uint32_t, kMaxDepth + 2> stack;
  std::array<double, kMaxDepth + 2> stack_t;
  int sp = 0;
  double t_root = 0.0;
  if (!slabEntry(nodes_[0].lo, nodes_[0].hi, seg, 1.0, t_root)) return Hit{};
  stack[0] = 0;
  stack_t[0] = t_root;
  sp = 1;
  while (sp > 0) {
    --sp;
    if (stack_t[std::size_t(sp)] > best.t) continue;
    const Node& node = nodes_[stack[std::size_t(sp)]];
    if (node.count > 0) {
      enterLeaf(node.first_or_right, node.count, a, b, skip, n_skip, best);
      continue;
    }
    const std::uint32_t left = std::uint32_t(&node - nodes_.data()) + 1, right = node.first_or_right;
    const double t_max = std::min(1.0, best.t);
    double tl = 0.0, tr = 0.0;
    const bool hl = slabEntry(nodes_[left].lo, nodes_[left].hi, seg, t_max, tl);
    const bool hr = slabEntry(nodes_[right].lo, nodes_[right].hi, seg, t_max, tr);
    // The nearer child on top, so its hits prune the farther one.
    if (hl && hr && tl < tr) {
      stack[std::size_t(sp)] = right, stack_t[std::size_t(sp++)] = tr;
      stack[std::size_t(sp)] = left, stack_t[std::size_t(sp++)] = tl;
    } else {
      if (hl) stack[std::size_t(sp)] = left, stack_t[std::size_t(sp++)] = tl;
      if (hr) stack[std::size_t(sp)] = right, stack_t[std::size_t(sp++)] = tr;
    }
  }
  return hitOf(best, a, b);
}

TriangleBvh::Nearest TriangleBvh::nearest(const Eigen::Vector3d& p, double max_distance) const {
  Nearest best;
  if (!p.allFinite() || !(max_distance >= 0.0)) return best;
  double best_d2 = max_distance * max_distance;
  auto boxDistance2 = [&p](const Node& node) {
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double lo = node.lo[std::size_t(k)], hi = node.hi[std::size_t(k)];
      const double e = p[k] < lo ? lo - p[k] : (p[k] > hi ? p[k] - hi : 0.0);
      d2 += e * e;
    }
    return d2;
  };
  std::array<std::uint32_t, kMaxDepth + 2> stack;
  int sp = 0;
  if (boxDistance2(nodes_[0]) > best_d2) return best;
  stack[std::size_t(sp++)] = 0;
  while (sp > 0) {
    const Node& node = nodes_[stack[std::size_t(--sp)]];
    if (boxDistance2(node) > best_d2) continue;
    if (node.count > 0) {
      for (std::uint32_t k = node.first_or_right; k < node.first_or_right + node.count; ++k) {
        const std::uint32_t tri = order_[k];
        const auto& t = (*triangles_)[tri];
        const Eigen::Vector3d& a = (*vertices_)[t[0]];
        const Eigen::Vector3d& b = (*vertices_)[t[1]];
        const Eigen::Vector3d& c = (*vertices_)[t[2]];
        const Eigen::Vector3d bc = mesh::closestBarycentric(a, b, c, p);
        const double d2 = (bc.x() * a + bc.y() * b + bc.z() * c - p).squaredNorm();
        if (d2 < best_d2 || (d2 == best_d2 && (!best.found || tri < best.triangle))) {
          best_d2 = d2;
          best.found = true;
          best.triangle = tri;
          best.barycentric = bc;
        }
      }
      continue;
    }
    const std::uint32_t left = std::uint32_t(&node - nodes_.data()) + 1, right = node.first_or_right;
    // The nearer child on top, so its triangles shrink the search before the farther one's.
    if (boxDistance2(nodes_[left]) < boxDistance2(nodes_[right])) {
      stack[std::size_t(sp++)] = right;
      stack[std::size_t(sp++)] = left;
    } else {
      stack[std::size_t(sp++)] = left;
      stack[std::size_t(sp++)] = right;
    }
  }
  best.distance = best.found ? std::sqrt(best_d2) : 0.0;
  return best;
}

}  // namespace thx::srv
