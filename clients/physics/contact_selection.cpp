#include "clients/physics/contact_selection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

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
  // std::max, not std::fmax: the terms are never NaN, and fmax is a library call (a box's
  // selection spent a tenth of its time in it).
  return 0.5 * std::max(t1, std::max(t2, t3));
}

// The candidates on their grid (texels stride_i apart along i, stride_j along j): the index of
// the candidate in each cell, -1 in a cell without one or outside the grid. Its cells are reused
// between calls (a resting ball costs no allocation per step); one grid at a time per thread.
class CandidateGrid {
 public:
  CandidateGrid(std::span<const ReliefCandidate> cand, long long stride_i, long long stride_j)
      : stride_i_(stride_i), stride_j_(stride_j), i0_(cand[0].i), j0_(cand[0].j) {
    long long i1 = i0_, j1 = j0_;
    for (const ReliefCandidate& c : cand) {
      i0_ = std::min(i0_, c.i), i1 = std::max(i1, c.i);
      j0_ = std::min(j0_, c.j), j1 = std::max(j1, c.j);
    }
    ni_ = (i1 - i0_) / stride_i_ + 1, nj_ = (j1 - j0_) / stride_j_ + 1;
    cells().assign(std::size_t(ni_ * nj_), -1);
    for (std::size_t k = 0; k < cand.size(); ++k) cells()[cell(gi(cand[k]), gj(cand[k]))] = int(k);
  }
  long long gi(const ReliefCandidate& c) const { return (c.i - i0_) / stride_i_; }
  long long gj(const ReliefCandidate& c) const { return (c.j - j0_) / stride_j_; }
  int at(long long gi, long long gj) const {
    return gi < 0 || gj < 0 || gi >= ni_ || gj >= nj_ ? -1 : cells()[cell(gi, gj)];
  }

 private:
  static std::vector<int>& cells() {
    thread_local std::vector<int> c;
    return c;
  }
  std::size_t cell(long long gi, long long gj) const { return std::size_t(gj * ni_ + gi); }
  long long stride_i_, stride_j_, i0_, j0_, ni_ = 0, nj_ = 0;
};

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

std::size_t selectShallowestBasins(std::span<const ReliefCandidate> cand, long long stride_i, long long stride_j,
                                   std::span<std::size_t> chosen) {
  if (cand.empty()) return 0;
  const std::size_t room = chosen.size();
  const CandidateGrid grid(cand, stride_i, stride_j);
  std::size_t count = 0;
  // Keeps as many of the deepest basins as `chosen` holds, in order (insertion into a short sorted list).
  for (std::size_t k = 0; k < cand.size(); ++k) {
    const long long gi = grid.gi(cand[k]), gj = grid.gj(cand[k]);
    bool basin = true;
    for (long long dj = -1; dj <= 1 && basin; ++dj)
      for (long long di = -1; di <= 1 && basin; ++di) {
        if (di == 0 && dj == 0) continue;
        const int n = grid.at(gi + di, gj + dj);
        // Ties go to the lower index, so a flat basin counts once.
        if (n >= 0 && (cand[std::size_t(n)].depth < cand[k].depth ||
                       (cand[std::size_t(n)].depth == cand[k].depth && std::size_t(n) < k)))
          basin = false;
      }
    if (!basin) continue;
    std::size_t at = count < room ? count++ : room;
    if (at == room) {
      if (!(cand[k].depth < cand[chosen[room - 1]].depth)) continue;
      at = room - 1;
    }
    while (at > 0 && cand[k].depth < cand[chosen[at - 1]].depth) chosen[at] = chosen[at - 1], --at;
    chosen[at] = k;
  }
  return count;
}

bool nearestClaims(const Eigen::Vector2d& start, const Eigen::Vector2d& bottom, std::span<const Eigen::Vector2d> others) {
  const double own = (bottom - start).squaredNorm();
  for (const Eigen::Vector2d& o : others)
    if ((bottom - o).squaredNorm() <= own) return false;
  return true;
}

std::size_t selectLyingRodContacts(std::span<const ReliefCandidate> cand, const Eigen::Vector2d& centre_xy,
                                   const Eigen::Vector2d& axis_xy, double band_m,
                                   std::array<std::size_t, kMaxReliefContacts>& chosen, bool flat_ends,
                                   double cap_half_length_m) {
  constexpr double kLyingCos = 0.5;  // within 60 degrees of the plane
  const double length = axis_xy.norm();
  if (cand.empty() || !(length > kLyingCos)) return 0;
  const Eigen::Vector2d along = axis_xy / length, across(-along.y(), along.x());
  double first = std::numeric_limits<double>::infinity(), last = -first;
  for (const ReliefCandidate& c : cand) {
    const double a = (xy(c) - centre_xy).dot(along);
    first = std::min(first, a), last = std::max(last, a);
  }
  // best[2 * end + side]: the deepest at that end (0: the first along the axis) on that side.
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  std::array<std::size_t, 4> best;
  best.fill(kNone);
  for (std::size_t k = 0; k < cand.size(); ++k) {
    const Eigen::Vector2d d = xy(cand[k]) - centre_xy;
    const double a = d.dot(along);
    const std::size_t side = d.dot(across) < 0.0 ? 0 : 1;
    for (std::size_t end = 0; end < 2; ++end) {
      if (end == 0 ? a > first + band_m : a < last - band_m) continue;
      std::size_t& b = best[2 * end + side];
      if (b == kNone || cand[k].depth < cand[b].depth) b = k;
    }
  }
  std::size_t n = 0;
  for (std::size_t b : best)
    if (b != kNone && std::find(chosen.begin(), chosen.begin() + std::ptrdiff_t(n), b) == chosen.begin() + std::ptrdiff_t(n))
      chosen[n++] = b;
  // Deepest first (an insertion sort: four at most).
  for (std::size_t i = 1; i < n; ++i)
    for (std::size_t j = i; j > 0 && cand[chosen[j]].depth < cand[chosen[j - 1]].depth; --j) std::swap(chosen[j], chosen[j - 1]);
  // The rod's deepest candidate between its ends is taken too, first, where it lies deeper than
  // the ends' by more than the texels' sampling leaves along a groove's walls (16 um at 0.31 mm
  // texels): on ground that bulges under the rod's middle (a ball) the ends' points alone let a
  // cylinder lying across a 1 cm ball sink 0.43 mm into it, held by their tilted normals, and a
  // capsule lying across a 5 cm sphere 60 um. A capsule's caps curve up at its ends, so its middle
  // lies deeper than its ends' points in any groove (taken there, it moved a capsule resting in one
  // by 9 um): its middle is compared with its straight part's ends, where the caps begin.
  if (n == 0 || !(flat_ends || cap_half_length_m > 0.0)) return n;
  // Its ends here: the candidates' extent along the axis (where the ground falls away beyond the
  // breaking threshold, on a bulge), within its straight part.
  const double straight = flat_ends ? std::numeric_limits<double>::infinity() : cap_half_length_m * length;
  const double lo = std::max(first, -straight), hi = std::min(last, straight);
  std::size_t deepest = kNone;
  double ends_depth = flat_ends ? cand[chosen[0]].depth : std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < cand.size(); ++k) {
    const double a = (xy(cand[k]) - centre_xy).dot(along);
    if (a > lo + band_m && a < hi - band_m) {
      if (deepest == kNone || cand[k].depth < cand[deepest].depth) deepest = k;
    } else if (!flat_ends && (std::fabs(a - lo) <= band_m || std::fabs(a - hi) <= band_m)) {
      ends_depth = std::min(ends_depth, cand[k].depth);
    }
  }
  constexpr double kDeeper = 50e-6;  // m
  if (deepest != kNone && std::isfinite(ends_depth) && cand[deepest].depth < ends_depth - kDeeper) {
    const std::size_t keep = std::min(n, kMaxReliefContacts - 1);
    for (std::size_t i = keep; i > 0; --i) chosen[i] = chosen[i - 1];
    chosen[0] = deepest;
    n = keep + 1;
  }
  return n;
}

void snapToBasins(std::span<const ReliefCandidate> cand, long long stride_i, long long stride_j,
                  std::span<std::size_t> chosen, BasinClaim claim) {
  if (cand.empty() || chosen.empty()) return;
  const CandidateGrid grid(cand, stride_i, stride_j);
  for (std::size_t c = 0; c < chosen.size(); ++c) {
    std::size_t index = chosen[c];
    // Strictly downhill, so it ends; at most one step per candidate.
    for (std::size_t guard = 0; guard < cand.size(); ++guard) {
      const long long gi = grid.gi(cand[index]), gj = grid.gj(cand[index]);
      std::size_t next = index;
      for (long long dj = -1; dj <= 1; ++dj)
        for (long long di = -1; di <= 1; ++di) {
          const int k = grid.at(gi + di, gj + dj);
          if (k >= 0 && cand[std::size_t(k)].depth < cand[next].depth) next = std::size_t(k);
        }
      if (next == index) break;
      index = next;
    }
    // A point whose basin is already chosen stays where it was: around a ball's single contact
    // the spread points are its look-ahead (a fast ball meets a dimple's far rim there first).
    if (claim == BasinClaim::NearestPoint) {
      std::array<Eigen::Vector2d, kMaxReliefContacts> others;
      std::size_t n_others = 0;
      for (std::size_t e = 0; e < chosen.size(); ++e)
        if (e != c) others[n_others++] = xy(cand[chosen[e]]);
      if (nearestClaims(xy(cand[chosen[c]]), xy(cand[index]), std::span(others.data(), n_others))) chosen[c] = index;
    } else if (std::find(chosen.begin(), chosen.begin() + std::ptrdiff_t(c), index) == chosen.begin() + std::ptrdiff_t(c)) {
      chosen[c] = index;
    }
  }
}

std::size_t BoxQuarters::chosen(std::array<std::size_t, kMaxReliefContacts>& ids) const {
  // The deepest first, then the quarter across from it, then the two beside (quarters are
  // numbered by two bits, one per axis). Ordered by depth instead, a box level on a flat relief
  // never came to rest: the solver, taking the points in that order, left it circling a few
  // nanometres at 7 um/s, the deepest corner going round once every four steps (bench_physics,
  // 1024² flat relief); in this order it stops.
  std::size_t first = 4;
  for (std::size_t q = 0; q < 4; ++q)
    if (std::isfinite(score_[q]) && (first == 4 || depth_[q] < depth_[first])) first = q;
  if (first == 4) return 0;
  std::size_t n = 0;
  for (std::size_t q : {first, first ^ 3u, first ^ 1u, first ^ 2u})
    if (std::isfinite(score_[q])) ids[n++] = id_[q];
  return n;
}

std::size_t selectBoxQuarterContacts(std::span<const ReliefCandidate> cand, BoxQuarters quarters,
                                     std::array<std::size_t, kMaxReliefContacts>& chosen) {
  if (cand.empty()) return 0;
  std::size_t deepest = 0;
  for (std::size_t k = 1; k < cand.size(); ++k)
    if (cand[k].depth < cand[deepest].depth) deepest = k;
  quarters.setDeepest(cand[deepest].depth, xy(cand[deepest]));
  for (std::size_t k = 0; k < cand.size(); ++k) quarters.offer(k, xy(cand[k]), cand[k].depth);
  return quarters.chosen(chosen);
}

}  // namespace thx::phys
