#include "clients/physics/contact_selection.hpp"

#include <cmath>

namespace thx::phys {

namespace {

Eigen::Vector2d xy(const ReliefCandidate& c) { return c.p_surface.head<2>(); }

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Area of the convex hull of up to 4 points given in order-agnostic form: for 4 points take the
// largest of the three ways to pair the diagonals (the hull's area for a convex quadrilateral).
double spreadArea(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                  const Eigen::Vector2d& d) {
  const double t1 = std::fabs(cross2(a - c, b - d));
  const double t2 = std::fabs(cross2(a - b, c - d));
  const double t3 = std::fabs(cross2(a - d, b - c));
  return 0.5 * std::fmax(t1, std::fmax(t2, t3));
}

}  // namespace

std::size_t selectReliefContacts(std::span<const ReliefCandidate> cand,
                                 std::array<std::size_t, kMaxReliefContacts>& chosen) {
  if (cand.empty()) return 0;
  std::size_t deepest = 0;
  for (std::size_t k = 1; k < cand.size(); ++k)
    if (cand[k].depth < cand[deepest].depth) deepest = k;
  chosen[0] = deepest;
  const Eigen::Vector2d a = xy(cand[deepest]);

  // Scores below this (m, m^2) mean "no new support": the candidates all sit on one point/line.
  constexpr double kMinSpread = 1e-9;

  std::size_t best = 0;
  double score = -1.0;
  for (std::size_t k = 0; k < cand.size(); ++k) {
    const double s = (xy(cand[k]) - a).norm();
    if (s > score) score = s, best = k;
  }
  if (score < kMinSpread) return 1;
  chosen[1] = best;
  const Eigen::Vector2d b = xy(cand[best]);

  score = -1.0;
  for (std::size_t k = 0; k < cand.size(); ++k) {
    const double s = std::fabs(cross2(b - a, xy(cand[k]) - a));
    if (s > score) score = s, best = k;
  }
  if (score < kMinSpread * kMinSpread) return 2;
  chosen[2] = best;
  const Eigen::Vector2d c = xy(cand[best]);

  const double base = 0.5 * std::fabs(cross2(b - a, c - a));
  score = -1.0;
  for (std::size_t k = 0; k < cand.size(); ++k) {
    const double s = spreadArea(a, b, c, xy(cand[k]));
    if (s > score) score = s, best = k;
  }
  if (score <= base + kMinSpread * kMinSpread) return 3;
  chosen[3] = best;
  return 4;
}

}  // namespace thx::phys
