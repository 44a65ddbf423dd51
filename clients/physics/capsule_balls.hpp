#pragma once
// Which balls of a capsule meet one triangle (ball_on_object_faces.hpp). A capsule is the segment
// [a, b] swept by a ball of radius r, so against a surface it is met as the balls centred on its
// segment, each met as a ball meets the surface (on a relief, lifted onto it). Where the segment
// comes nearest the triangle off its run over it (beside an edge), that one ball, as Bullet's
// sphere-triangle contact for it. Where the segment runs over the triangle (inside the prism the
// triangle sweeps along its normal) the ball to meet is the one whose gap to the relief is least,
// which the relief decides, not the plane: a capsule lying across grooves rests on their ridges
// though its ends lie over grooves. So the run is searched (leastOnHalves), and each half of it
// gives one ball, so that a capsule lying along a face stands on two points as on a line, as
// Bullet's capsule-box contact gives it two. A sphere is a capsule with a == b: its centre only.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>

namespace thx::phys {

// Where segment [a, b] lies over triangle (p0, p1, p2); parameters along it, 0 at a, 1 at b.
struct SegmentOverTriangle {
  double nearest_t = 0.0;  // the segment's point nearest the triangle
  bool runs_over = false;  // whether some of it lies over the triangle (in its prism)
  double lo = 0.0, hi = 0.0;  // that part
};
SegmentOverTriangle segmentOverTriangle(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                                        const Eigen::Vector3d& a, const Eigen::Vector3d& b);

// The distance from point p to triangle (p0, p1, p2).
double distanceToTriangle(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                          const Eigen::Vector3d& p);

// The parameters (s along [a, b], u along [c, d], each in [0, 1]) of the closest points of two
// segments; a degenerate segment is its point.
void closestOnSegments(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                       const Eigen::Vector3d& d, double& s, double& u);

struct RunBalls {
  std::array<double, 2> t{};
  int count = 0;
};

// Where gap(t) is least on each half of [lo, hi]: sampled every `step` (at most kMaxRunSamples
// samples over the run), the least sample of each half (the one nearer that half's outer end on a
// tie within `tie`) refined by parabolas over the samples beside it. One where the run is a point,
// or both halves find the same place.
inline constexpr int kMaxRunSamples = 256;
template <class Gap>
RunBalls leastOnHalves(double lo, double hi, double step, double tie, const Gap& gap) {
  RunBalls balls;
  if (!(hi - lo > 0.0)) {  // a point (a sphere's centre)
    balls.t[0] = lo;
    balls.count = 1;
    return balls;
  }
  const int intervals = step > 0.0 ? int(std::clamp(std::ceil((hi - lo) / step), 2.0, double(kMaxRunSamples - 1))) : 2;
  const double h = (hi - lo) / intervals;
  const auto at = [&](int k) { return k == intervals ? hi : lo + k * h; };
  const int middle = intervals / 2;
  // The lower half scanned from lo up, the upper from hi down.
  const auto least = [&](int from, int to, int direction) {
    int best = from;
    double best_gap = gap(at(from));
    for (int k = from + direction; direction > 0 ? k <= to : k >= to; k += direction) {
      const double g = gap(at(k));
      if (g < best_gap - tie) {
        best_gap = g;
        best = k;
      }
    }
    // Refined by parabolas through the least and the samples beside it (three rounds): a ball
    // meets a crest on a sphere cap of its own, smooth at its top, so a parabola finds it.
    double x0 = at(std::max(best - 1, 0)), x1 = at(best), x2 = at(std::min(best + 1, intervals));
    double g0 = gap(x0), g1 = best_gap, g2 = gap(x2);
    for (int round = 0; round < 3 && x0 < x1 && x1 < x2; ++round) {
      const double d0 = x1 - x0, d2 = x2 - x1;
      const double denominator = d0 * (g2 - g1) + d2 * (g0 - g1);
      if (!(denominator > 0.0)) break;  // not convex there: the least sample stands
      const double x = std::clamp(x1 - 0.5 * (d0 * d0 * (g2 - g1) - d2 * d2 * (g0 - g1)) / denominator, x0, x2);
      if (x == x1 || x == x0 || x == x2) break;
      const double g = gap(x);
      if (g < g1) {  // the new least, its neighbours the bracket's nearer ends
        (x < x1 ? x2 : x0) = x1;
        (x < x1 ? g2 : g0) = g1;
        x1 = x;
        g1 = g;
      } else {
        (x < x1 ? x0 : x2) = x;
        (x < x1 ? g0 : g2) = g;
      }
    }
    return g1 < best_gap - tie ? x1 : at(best);
  };
  balls.t[0] = least(0, middle, 1);
  balls.t[1] = least(intervals, middle, -1);
  balls.count = std::fabs(balls.t[1] - balls.t[0]) > 1e-9 * (hi - lo) ? 2 : 1;
  return balls;
}

}  // namespace thx::phys
