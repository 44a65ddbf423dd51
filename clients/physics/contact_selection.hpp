#pragma once
// Choosing which rasterised relief contacts go into Bullet's manifold (at most 4 points, btPersistentManifold's cache size).
//
// Rule: the deepest candidate first (the one that must be resolved), then the candidates that
// spread the support the most: the farthest from the first, the farthest from the line through
// both, then the one that adds the most area. A box resting flat gets its four corners, a ball
// bridging a small dimple gets points around the rim, a ball on a slope gets its deepest point.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <limits>
#include <span>

namespace thx::phys {

struct ReliefCandidate {
  Eigen::Vector3d p_surface = Eigen::Vector3d::Zero();  // texel centre on the relief, plane frame
  Eigen::Vector3d n_local = Eigen::Vector3d::UnitZ();   // relief normal there, plane frame
  double depth = 0.0;  // object's lowest z minus the relief height: < 0 = penetrating (along the plane normal)
  long long i = 0, j = 0;  // unwrapped texel index (the candidate's texel)
};

inline constexpr std::size_t kMaxReliefContacts = 4;

// Fills `chosen` with indices into `candidates`; returns how many (0 if there are none).
std::size_t selectReliefContacts(std::span<const ReliefCandidate> candidates,
                                 std::array<std::size_t, kMaxReliefContacts>& chosen);

// The basins of the pair's depth closest to closing: the candidates no deeper than any of their
// eight neighbours on the candidate grid (texels stride_i apart along i, stride_j along j; a
// missing neighbour is open), the deepest first, then the next shallowest, as many as `chosen`
// holds. For a ball with a bump map, whose supports are bump tips: the spread rule's points, walked
// to their basins, stood 40-280 µm open at the footprint's edge while the next tip to touch,
// nearer the centre, was left out until it had entered 9 µm deep (docs/physics.md, Known gaps).
std::size_t selectShallowestBasins(std::span<const ReliefCandidate> candidates, long long stride_i, long long stride_j,
                                   std::span<std::size_t> chosen);

// A rod lying on the relief (a capsule, or a cylinder on its side, its axis within 60 degrees of
// the plane: `axis_xy` the axis's direction in the plane, of length cos(its tilt), `centre_xy` its
// centre) touches along lines parallel to its axis, one on each wall of a groove it lies in: at
// each of its two ends (the candidates within `band_m` of the extreme along the axis) the
// deepest candidate on each side of the axis; and the deepest candidate between its ends where
// it lies 50 um deeper than those (ground that bulges under the rod's middle, a ball): for a
// cylinder (`flat_ends`) its ends' points, for a capsule (`cap_half_length_m`, half the distance
// between its caps' centres; 0: none) the deepest within the band of its straight part's ends;
// up to four, deepest first. Returns 0 for a rod
// steeper than that (the general rule then). The spread rule picked the fringe texels farthest up
// a groove's walls, with gaps of 0.1 mm, and left one wall at one end holding a cylinder: it
// rattled between its ends and rested 54 µm into the walls (bench_rod_in_groove, 2026-12-02); its
// basin walks along a tilted rod's contact line ran to the far end.
std::size_t selectLyingRodContacts(std::span<const ReliefCandidate> candidates, const Eigen::Vector2d& centre_xy,
                                   const Eigen::Vector2d& axis_xy, double band_m,
                                   std::array<std::size_t, kMaxReliefContacts>& chosen, bool flat_ends = false,
                                   double cap_half_length_m = 0.0);

// For a sphere, whose contacts are isolated points, and a box on a bumpy relief (it rests on the
// bumps' tops; before, it stood on its deepest point and rocked): moves each chosen candidate downhill in
// depth, over its 8 neighbours on the candidate grid (texels stride_i apart along i, stride_j along
// j), to the bottom of its
// basin, unless an earlier chosen point holds that basin (then it stays: around a single contact
// the spread points are look-ahead for a fast ball). The spread rule alone picks a fringe texel
// of a second wall (a ball resting in a groove
// on both walls): a point slightly off the contact, computed unlike the refined deepest one, so
// the two walls' contacts disagreed and the ball rattled between them in a two-step cycle
// (±55 nm, read as 0.11 mm/s at 1 kHz; refined basin bottoms: ±7 nm, 0.014 mm/s).
//
// Which basin a point may take (BasinClaim):
// - SameTexel (a sphere): any basin no earlier point went to.
// - NearestPoint (a box): only a basin whose bottom is nearer (in the plane) to the point than to
//   every other chosen point (where an earlier one went, where a later one stands). A basin
//   nearer another point is that point's; going there gathers the contacts and loses the spread
//   they stand for. On a sloping relief a box's walks cross its footprint (a roll of a µm already
//   makes one edge the deepest) and end in basins of the heights' rounding along that edge: its
//   four contacts stood on one edge, the box rocked from edge to edge each step and crept down
//   a 0.28 slope at friction 0.3 (up to 9 mm in 2 s), and a push up a 26.6° slope moved it at
//   0.65-0.92 of its weight where friction holds it to 0.94.
enum class BasinClaim { SameTexel, NearestPoint };
void snapToBasins(std::span<const ReliefCandidate> candidates, long long stride_i, long long stride_j,
                  std::span<std::size_t> chosen, BasinClaim claim = BasinClaim::SameTexel);

// A plain box on a relief (the plane, a mesh's chart; relief_collision.cpp) rests on the lowest
// point of each quarter of its footprint, about its centre `centre_xy` along its axes `axis_a`,
// `axis_b` as they lie in the plane: in each, the candidate lowest in depth less `prefer_spread`
// times its distance from the centre, the most spread of those about as deep. In the quarter of
// the deepest candidate only candidates within `depth_tolerance` of its depth take part (the
// most spread of them as elsewhere), so what must be resolved is resolved to that tolerance. Up
// to four, deepest first. A box on sharp V-ridges rests on the crests in each quarter.
//
// The spread rule's corners stood on texels down the outer ridges' flanks, up to 27 um above its
// support, and the block rested on one point a step, a different ridge each step: never at rest,
// it moved 0.2-3.1 mm in 0.9 s along the grooves on a mesh, 0.02-0.34 mm in 0.9 s on the plane
// (docs/physics.md, "A plain box on sharp ridges"). The tolerance is the relief's depth step: on a
// uniform slope the stored heights' rounding (0.3 um at 16 bits of 2 cm) made a texel one in from
// a corner the deepest, a different side each step, and a box pushed up the slope at 0.91 of the
// weight its friction holds to 0.94 moved 0.24 mm in 0.3 s (without the tolerance); with it the
// four corners hold it.

// The farther of two candidates is preferred where their depths differ by less than this per metre
// between their distances from the centre (a tilt of 1 mrad): the corners of a box level on flat
// ground, the outer crests of ridges over texels down their flanks. The block on the grooved slab
// mesh, released at eight positions 0.05 mm apart, moved 1.6-9.7 um in 0.9 s (0.2-3.1 mm with the
// spread rule); a first version (quarters along the chart's axes, points then snapped to their
// basins) held it as well at 0.3, 1 and 3 mrad.
inline constexpr double kPreferSpread = 1e-3;

// The rule's bookkeeping: the deepest candidate is found first; then every candidate that may win
// is offered, in any order, named by its place in scan order (`id`: of equal scores the first in
// scan order wins, whatever the order of the offers). selectBoxQuarterContacts offers all;
// box_relief_contacts.cpp only those its rows show can win.
class BoxQuarters {
 public:
  // `reach`: no candidate lies farther than this from the centre (it lets most offers be refused
  // without their distance).
  BoxQuarters(const Eigen::Vector2d& centre_xy, const Eigen::Vector2d& axis_a, const Eigen::Vector2d& axis_b,
              double prefer_spread, double depth_tolerance, double reach)
      : centre_(centre_xy), axis_a_(axis_a), axis_b_(axis_b), prefer_spread_(prefer_spread), tolerance_(depth_tolerance),
        most_preferred_(prefer_spread * reach * (1.0 + 1e-9)) {}
  int quarterOf(const Eigen::Vector2d& xy) const {
    const Eigen::Vector2d d = xy - centre_;
    return (d.dot(axis_a_) < 0.0 ? 0 : 1) + (d.dot(axis_b_) < 0.0 ? 0 : 2);
  }
  // Once, before any offer: the deepest candidate's depth and where it lies.
  void setDeepest(double depth, const Eigen::Vector2d& xy) { deepest_ = depth, deepest_quarter_ = quarterOf(xy); }
  double depthTolerance() const { return tolerance_; }
  const Eigen::Vector2d& centre() const { return centre_; }
  std::array<Eigen::Vector2d, 2> axes() const { return {axis_a_, axis_b_}; }
  // Candidate `id` (its place in scan order) at `xy`, `depth`.
  void offer(std::size_t id, const Eigen::Vector2d& xy, double depth) {
    const int q = quarterOf(xy);
    if (q == deepest_quarter_ && !(depth <= deepest_ + tolerance_)) return;
    if (depth - most_preferred_ >= score_[std::size_t(q)]) return;  // cannot score lower
    const double s = depth - prefer_spread_ * (xy - centre_).norm();
    const std::size_t k = std::size_t(q);
    if (s < score_[k] || (s == score_[k] && id < id_[k])) score_[k] = s, depth_[k] = depth, id_[k] = id;
  }
  // Whether no candidate at least `depth` deep and at most `distance` from the centre can change
  // anything: every quarter already has a lower score.
  bool refuses(double depth, double distance) const {
    const double score = depth - prefer_spread_ * distance * (1.0 + 1e-9);
    return score > score_[0] && score > score_[1] && score > score_[2] && score > score_[3];
  }
  // The winners' ids, the deepest first (of equal depths, the lower quarter), then the quarter
  // across from it, then the two beside it; how many.
  std::size_t chosen(std::array<std::size_t, kMaxReliefContacts>& ids) const;

 private:
  Eigen::Vector2d centre_, axis_a_, axis_b_;
  double prefer_spread_, tolerance_, most_preferred_;
  double deepest_ = 0.0;
  int deepest_quarter_ = -1;
  std::array<double, 4> score_ = filled(std::numeric_limits<double>::infinity());
  std::array<double, 4> depth_{};
  std::array<std::size_t, 4> id_{};
  static std::array<double, 4> filled(double v) { return {v, v, v, v}; }
};

// The rule over every candidate, in their order; `quarters` is the box's (quartersUnder,
// box_relief_contacts.hpp), not yet fed.
std::size_t selectBoxQuarterContacts(std::span<const ReliefCandidate> candidates, BoxQuarters quarters,
                                     std::array<std::size_t, kMaxReliefContacts>& chosen);

// Whether a point that walked from `start` to `bottom` may take that basin under
// BasinClaim::NearestPoint: `others` are the other chosen points where they are. A standing
// cylinder's rim (end_face_contacts.cpp) and snapToBasins decide with this one function.
bool nearestClaims(const Eigen::Vector2d& start, const Eigen::Vector2d& bottom, std::span<const Eigen::Vector2d> others);

}  // namespace thx::phys
