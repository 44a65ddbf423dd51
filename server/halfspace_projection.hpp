#pragma once
// The proxy's constraint solver: the point closest to the tip inside the intersection of up to
// four half-spaces n_i . x >= d_i (the local planes of the surface around the proxy). This is a
// tiny convex QP; we enumerate active sets of size 0..3 and return the one that satisfies the
// KKT conditions (feasible, non-negative multipliers). Projection onto a convex set is
// 1-Lipschitz, so the proxy, and with it the force, moves continuously with the tip: no force
// jump when the tip crosses a crease (docs/design.md §5).
// Real-time safe: fixed-size arrays, no allocation, at most 14 small solves.
#include <Eigen/Core>
#include <array>

namespace thx::srv {

inline constexpr int kMaxHalfspaces = 4;

struct Halfspace {
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();  // unit, pointing into the allowed side
  double d = 0.0;
};

struct Projection {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  unsigned active_mask = 0;  // bit i set: half-space i is active (x on its plane)
  bool inside = false;       // the tip was already inside every half-space
  bool solved = false;       // false only if every candidate active set was numerically degenerate
};

Projection projectOntoHalfspaces(const Eigen::Vector3d& tip, const std::array<Halfspace, kMaxHalfspaces>& planes,
                                 int count);

}  // namespace thx::srv
