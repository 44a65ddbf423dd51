#include "server/coupling_projection.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

namespace thx::srv {

using Vector6d = Eigen::Matrix<double, 6, 1>;

namespace {

constexpr int kMaxActive = 12;
using ActiveMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxActive, kMaxActive>;
using ActiveVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxActive, 1>;

// Gauss-Seidel converges slowly once several contacts hold the tool (a shaft across two ridges:
// the rotation couples them), so its answer names the contacts that hold and this solves for
// exactly those: the projection onto their planes, (A_S A_S^T) lambda_S = b_S - A_S x*. A set
// whose multipliers are not all >= 0 loses its most negative one, and a contact left inside joins
// it (the most violated first), at most kPolishRounds times; the answer is kept only if it is one
// (every multiplier >= 0, every contact outside within the tolerance). A redundant set (more
// contacts than the six motions they constrain) gets a relative 1e-12 regularisation.
bool polishActiveSet(const std::array<Vector6d, kMaxToolContacts>& a, const ToolContacts& contacts,
                     const Vector6d& x_target, PoseStep& step, Vector6d& x, const ProjectionSettings& settings) {
  constexpr int kPolishRounds = 8;
  std::array<bool, kMaxToolContacts> in{};
  int m = 0;
  for (int i = 0; i < contacts.count; ++i) {
    in[std::size_t(i)] = step.lambda_n[std::size_t(i)] > 0.0;
    m += in[std::size_t(i)];
  }
  for (int round = 0; round < kPolishRounds; ++round) {
    if (m == 0 || m > kMaxActive) return false;
    std::array<int, kMaxActive> active{};
    int k = 0;
    for (int i = 0; i < contacts.count; ++i)
      if (in[std::size_t(i)]) active[std::size_t(k++)] = i;
    ActiveMatrix gram(m, m);
    ActiveVector rhs(m);
    for (int r = 0; r < m; ++r) {
      const Vector6d& ar = a[std::size_t(active[std::size_t(r)])];
      rhs(r) = -contacts.c[std::size_t(active[std::size_t(r)])].gap_m - ar.dot(x_target);
      for (int c = 0; c < m; ++c) gram(r, c) = ar.dot(a[std::size_t(active[std::size_t(c)])]);
    }
    gram.diagonal().array() += 1e-12 * gram.trace() / m;
    const ActiveVector lambda = gram.ldlt().solve(rhs);
    if (!lambda.allFinite()) return false;
    int most_negative = -1;
    for (int r = 0; r < m; ++r)
      if (lambda(r) < 0.0 && (most_negative < 0 || lambda(r) < lambda(most_negative))) most_negative = r;
    if (most_negative >= 0) {
      in[std::size_t(active[std::size_t(most_negative)])] = false;
      --m;
      continue;
    }
    Vector6d polished = x_target;
    for (int r = 0; r < m; ++r) polished += lambda(r) * a[std::size_t(active[std::size_t(r)])];
    int most_violated = -1;
    double worst = settings.tolerance_m;
    for (int i = 0; i < contacts.count; ++i) {
      const double violation = -contacts.c[std::size_t(i)].gap_m - a[std::size_t(i)].dot(polished);
      if (violation > worst) {
        worst = violation;
        most_violated = i;
      }
    }
    if (most_violated >= 0) {
      in[std::size_t(most_violated)] = true;
      ++m;
      continue;
    }
    x = polished;
    step.lambda_n.fill(0.0);
    for (int r = 0; r < m; ++r) step.lambda_n[std::size_t(active[std::size_t(r)])] = lambda(r);
    step.converged = true;
    return true;
  }
  return false;
}

}  // namespace

PoseStep projectToolMotion(const Eigen::Vector3d& dx_target, const Eigen::Vector3d& dtheta_target,
                           const ToolContacts& contacts, const Eigen::Vector3d& centre, const CouplingGains& gains,
                           const ProjectionSettings& settings) {
  PoseStep step;
  const double sk = std::sqrt(gains.k_n_per_m);
  const double skr = std::sqrt(gains.k_rot_nm_per_rad);
  // A rotational gain of zero: the tool turns freely (its orientation is the contacts' to choose),
  // which the scaled problem cannot express; such a tool keeps its orientation instead.
  const bool turns = skr > 0.0;
  Vector6d x;
  x << sk * dx_target, (turns ? skr : 0.0) * dtheta_target;
  const Vector6d x_target = x;
  std::array<Vector6d, kMaxToolContacts> a;
  std::array<double, kMaxToolContacts> a_norm2{};
  for (int i = 0; i < contacts.count; ++i) {
    const ToolContact& c = contacts.c[std::size_t(i)];
    Vector6d row;
    row << c.normal / sk, turns ? Eigen::Vector3d((c.point - centre).cross(c.normal) / skr) : Eigen::Vector3d::Zero();
    a[std::size_t(i)] = row;
    a_norm2[std::size_t(i)] = row.squaredNorm();
  }
  // Sweeps in rounds; after each, the exact solve on the contacts found holding. Most ticks end
  // after the first round; a hard set (several contacts coupled by the rotation) takes more.
  bool done = false;
  while (!done && step.sweeps < settings.max_sweeps) {
    double largest_change = 0.0;
    for (int sweep = 0; sweep < settings.sweeps_per_round && step.sweeps < settings.max_sweeps; ++sweep) {
      ++step.sweeps;
      largest_change = 0.0;
      for (int i = 0; i < contacts.count; ++i) {
        const std::size_t k = std::size_t(i);
        // a . x >= -gap, with a = J / sqrt(gains): a violation is a penetration in metres.
        const double violation = -contacts.c[k].gap_m - a[k].dot(x);
        const double lambda = std::max(0.0, step.lambda_n[k] + violation / a_norm2[k]);
        const double change = lambda - step.lambda_n[k];
        if (change != 0.0) {
          x += change * a[k];
          step.lambda_n[k] = lambda;
          largest_change = std::max(largest_change, std::abs(change) * std::sqrt(a_norm2[k]));
        }
      }
      if (largest_change <= settings.tolerance_m) break;
    }
    Vector6d polished = x;
    PoseStep trial = step;
    if (polishActiveSet(a, contacts, x_target, trial, polished, settings)) {
      x = polished;
      step = trial;
      done = true;
    } else if (largest_change <= settings.tolerance_m) {
      step.converged = true;
      done = true;
    }
  }
  step.residual_m = 0.0;
  for (int i = 0; i < contacts.count; ++i)
    step.residual_m = std::max(step.residual_m, -contacts.c[std::size_t(i)].gap_m - a[std::size_t(i)].dot(x));
  step.dx = x.head<3>() / sk;
  step.dtheta = turns ? Eigen::Vector3d(x.tail<3>() / skr) : Eigen::Vector3d::Zero();
  return step;
}

}  // namespace thx::srv
