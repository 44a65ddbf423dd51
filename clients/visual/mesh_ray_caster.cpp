#include "clients/visual/mesh_ray_caster.hpp"

#include <algorithm>
#include <array>
#include <limits>

namespace thx::visual {
namespace {

// Slab test: the ray's entry parameter into the box, or +infinity when it misses it before t_max.
double boxEntry(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& o, const Eigen::Vector3d& inv_d, double t_max) {
  double lo = 0.0, hi = t_max;
  for (int k = 0; k < 3; ++k) {
    double t0 = (box.min()[k] - o[k]) * inv_d[k], t1 = (box.max()[k] - o[k]) * inv_d[k];
    if (t0 > t1) std::swap(t0, t1);
    // NaN (0 * inf: the origin on a slab's plane, the ray parallel to it) keeps the interval.
    if (t0 > lo) lo = t0;
    if (t1 < hi) hi = t1;
  }
  return lo <= hi ? lo : std::numeric_limits<double>::infinity();
}

}  // namespace

MeshRayCaster::MeshRayCaster(const mesh::TexturedMesh& mesh) : mesh_(&mesh) {
  const std::uint32_t n = std::uint32_t(mesh.triangles.size());
  order_.resize(n);
  centroids_.resize(n);
  for (std::uint32_t k = 0; k < n; ++k) {
    order_[k] = k;
    const mesh::Triangle& t = mesh.triangles[k];
    centroids_[k] = (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0;
  }
  nodes_.reserve(2 * std::size_t(n / kLeafSize + 1));
  nodes_.emplace_back();
  if (n > 0) build(0, 0, n, 0);
}

void MeshRayCaster::build(std::uint32_t node, std::uint32_t begin, std::uint32_t end, int depth) {
  Eigen::AlignedBox3d box, centres;
  for (std::uint32_t k = begin; k < end; ++k) {
    const mesh::Triangle& t = mesh_->triangles[order_[k]];
    for (std::uint32_t c : t) box.extend(mesh_->positions[c]);
    centres.extend(centroids_[order_[k]]);
  }
  nodes_[node].box = box;
  if (end - begin <= kLeafSize || depth >= kMaxDepth) {
    nodes_[node].first = begin;
    nodes_[node].count = end - begin;
    return;
  }
  Eigen::Index axis = 0;
  centres.sizes().maxCoeff(&axis);
  const std::uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](std::uint32_t a, std::uint32_t b) { return centroids_[a][axis] < centroids_[b][axis]; });
  const std::uint32_t left = std::uint32_t(nodes_.size());
  nodes_.emplace_back();
  nodes_.emplace_back();
  nodes_[node].first = left;
  nodes_[node].count = 0;
  build(left, begin, mid, depth + 1);
  build(left + 1, mid, end, depth + 1);
}

std::optional<MeshRayHit> MeshRayCaster::firstHit(const Eigen::Vector3d& o, const Eigen::Vector3d& d) const {
  std::optional<MeshRayHit> best;
  if (order_.empty()) return best;
  double t_best = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d inv_d = d.cwiseInverse();
  std::array<std::uint32_t, 2 * kMaxDepth + 2> stack{};
  int top = 0;
  stack[std::size_t(top++)] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[std::size_t(--top)]];
    if (boxEntry(node.box, o, inv_d, t_best) == std::numeric_limits<double>::infinity()) continue;
    if (node.count == 0) {
      // The nearer child last, so it is visited first and shrinks t_best for the other.
      const double a = boxEntry(nodes_[node.first].box, o, inv_d, t_best);
      const double b = boxEntry(nodes_[node.first + 1].box, o, inv_d, t_best);
      const std::uint32_t near = a <= b ? node.first : node.first + 1;
      stack[std::size_t(top++)] = near == node.first ? node.first + 1 : node.first;
      stack[std::size_t(top++)] = near;
      continue;
    }
    for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
      // Moller-Trumbore; det > 0 is the counter-clockwise side facing the origin.
      const mesh::Triangle& tri = mesh_->triangles[order_[k]];
      const Eigen::Vector3d& p0 = mesh_->positions[tri[0]];
      const Eigen::Vector3d e1 = mesh_->positions[tri[1]] - p0, e2 = mesh_->positions[tri[2]] - p0;
      const Eigen::Vector3d pv = d.cross(e2);
      const double det = e1.dot(pv);
      if (!(det > 0.0)) continue;
      const Eigen::Vector3d s = o - p0;
      const double u = s.dot(pv) / det;
      if (u < 0.0 || u > 1.0) continue;
      const Eigen::Vector3d q = s.cross(e1);
      const double v = d.dot(q) / det;
      if (v < 0.0 || u + v > 1.0) continue;
      const double t = e2.dot(q) / det;
      if (t <= 0.0 || t >= t_best) continue;
      t_best = t;
      best = MeshRayHit{order_[k], Eigen::Vector3d(1.0 - u - v, u, v), t};
    }
  }
  return best;
}

}  // namespace thx::visual
