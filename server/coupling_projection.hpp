#pragma once
// The pen with extent's constraint solver (capsule_tool.hpp): the small rigid motion of the tool
// (translation dx of its centre, rotation dtheta about it) closest to the motion that would bring
// it onto the device's pose, in the virtual coupling's own metric
//     1/2 k |dx - dx*|^2 + 1/2 k_rot |dtheta - dtheta*|^2,
// among the motions that keep every contact out of the surface, linearised:
//     n_i . (dx + dtheta x (p_i - c)) >= -gap_i.
// The quasi-static 6-DOF god object (Ortega, Redon and Coquillart 2007): the tool has no mass, so it
// cannot ring against the coupling, and the multipliers are the contact forces (N) that balance the
// coupling's spring: k (dx* - dx) + sum lambda_i n_i = 0, and the same for the torque.
//
// Solved in the coupling's scaled coordinates (x = sqrt(k) dx, sqrt(k_rot) dtheta), where the
// problem is a projection onto a polyhedron: projected Gauss-Seidel on the multipliers (rounds of
// sweeps_per_round sweeps of the contacts, each 2 x 6 multiply-adds a contact) finds which contacts
// hold, then the projection onto exactly those is solved (a small LDLT, at most 12 contacts, a few
// rounds of adding and dropping one) and kept if it satisfies every contact; else another round,
// up to max_sweeps. A residual says how far it got. Real-time safe: no allocation (fixed-capacity matrices).
#include <Eigen/Core>
#include <array>

#include "server/capsule_contacts.hpp"

namespace thx::srv {

struct CouplingGains {
  double k_n_per_m = 0.0;
  double k_rot_nm_per_rad = 0.0;
};

struct PoseStep {
  Eigen::Vector3d dx = Eigen::Vector3d::Zero();
  Eigen::Vector3d dtheta = Eigen::Vector3d::Zero();
  std::array<double, kMaxToolContacts> lambda_n{};  // each contact's force along its normal (>= 0)
  int sweeps = 0;
  double residual_m = 0.0;  // the largest penetration the linearised contacts are left with
  bool converged = false;
};

struct ProjectionSettings {
  int sweeps_per_round = 10;  // then the exact solve on the contacts found holding (coupling_projection.cpp)
  int max_sweeps = 80;
  double tolerance_m = 1e-9;  // penetration of a linearised contact, and change of the motion per sweep
};

// centre: the tool's centre, the point rotations turn about (same frame as the contacts).
PoseStep projectToolMotion(const Eigen::Vector3d& dx_target, const Eigen::Vector3d& dtheta_target,
                           const ToolContacts& contacts, const Eigen::Vector3d& centre, const CouplingGains& gains,
                           const ProjectionSettings& settings);

}  // namespace thx::srv
