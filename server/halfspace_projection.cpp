#include "server/halfspace_projection.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace thx::srv {

namespace {

constexpr double kFeasibleTol = 1e-12;  // metres: below encoder resolution by 7 orders
constexpr double kGramDetMin = 1e-10;   // rejects near-parallel / coplanar normal sets

bool feasible(const Eigen::Vector3d& x, const std::array<Halfspace, kMaxHalfspaces>& planes, int count) {
  for (int i = 0; i < count; ++i) {
    if (planes[std::size_t(i)].n.dot(x) < planes[std::size_t(i)].d - kFeasibleTol) return false;
  }
  return true;
}

// Closest point to `tip` on the intersection of the planes in `mask` (as equalities), with the
// multipliers; false if degenerate or a multiplier is negative (that plane would pull inward).
template <int K>
bool solveActive(const Eigen::Vector3d& tip, const std::array<Halfspace, kMaxHalfspaces>& planes, const int (&idx)[K],
                 Eigen::Vector3d& x) {
  Eigen::Matrix<double, 3, K> N;
  Eigen::Matrix<double, K, 1> r;
  for (int k = 0; k < K; ++k) {
    const Halfspace& h = planes[std::size_t(idx[k])];
    N.col(k) = h.n;
    r(k) = h.d - h.n.dot(tip);
  }
  const Eigen::Matrix<double, K, K> G = N.transpose() * N;
  if (!(std::fabs(G.determinant()) > kGramDetMin)) return false;
  const Eigen::Matrix<double, K, 1> lambda = G.inverse() * r;
  for (int k = 0; k < K; ++k) {
    if (!(lambda(k) >= 0.0)) return false;
  }
  x = tip + N * lambda;
  return true;
}

}  // namespace

Projection projectOntoHalfspaces(const Eigen::Vector3d& tip, const std::array<Halfspace, kMaxHalfspaces>& planes,
                                 int count) {
  Projection out;
  out.x = tip;
  if (count <= 0 || feasible(tip, planes, count)) {
    out.inside = true;
    out.solved = true;
    return out;
  }
  Eigen::Vector3d x;
  // One active plane.
  for (int i = 0; i < count; ++i) {
    const int idx[1] = {i};
    if (solveActive<1>(tip, planes, idx, x) && feasible(x, planes, count)) {
      out.x = x;
      out.active_mask = 1u << i;
      out.solved = true;
      return out;
    }
  }
  // Two: a crease line.
  for (int i = 0; i < count; ++i) {
    for (int j = i + 1; j < count; ++j) {
      const int idx[2] = {i, j};
      if (solveActive<2>(tip, planes, idx, x) && feasible(x, planes, count)) {
        out.x = x;
        out.active_mask = (1u << i) | (1u << j);
        out.solved = true;
        return out;
      }
    }
  }
  // Three: a corner.
  for (int i = 0; i < count; ++i) {
    for (int j = i + 1; j < count; ++j) {
      for (int k = j + 1; k < count; ++k) {
        const int idx[3] = {i, j, k};
        if (solveActive<3>(tip, planes, idx, x) && feasible(x, planes, count)) {
          out.x = x;
          out.active_mask = (1u << i) | (1u << j) | (1u << k);
          out.solved = true;
          return out;
        }
      }
    }
  }
  return out;
}

}  // namespace thx::srv
