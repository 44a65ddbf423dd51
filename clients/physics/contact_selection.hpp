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

// A rod lying on the relief (a capsule, or a cylinder on its side, its axis within 60 degrees of
// the plane: `axis_xy` the axis's direction in the plane, of length cos(its tilt), `centre_xy` its
// centre) touches along lines parallel to its axis, one on each wall of a groove it lies in: at
// each of its two ends (the candidates within `band_m` of the extreme along the axis) the
// deepest candidate on each side of the axis; up to four, deepest first. Returns 0 for a rod
// steeper than that (the general rule then). The spread rule picked the fringe texels farthest up
// a groove's walls, with gaps of 0.1 mm, and left one wall at one end holding a cylinder: it
// rattled between its ends and rested 54 µm into the walls (bench_rod_in_groove, 2026-12-02); its
// basin walks along a tilted rod's contact line ran to the far end.
std::size_t selectLyingRodContacts(std::span<const ReliefCandidate> candidates, const Eigen::Vector2d& centre_xy,
                                   const Eigen::Vector2d& axis_xy, double band_m,
                                   std::array<std::size_t, kMaxReliefContacts>& chosen);

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

// A box on a relief's chart of a mesh (relief_collision.cpp): the deepest candidate, then in each
// other quarter of the box's footprint (about its centre `centre_xy`, along its axes `axis_a`,
// `axis_b` as they lie in the plane) the candidate lowest in depth less `prefer_spread` times its
// distance from the centre: the most spread of those about as deep. A box on sharp V-ridges rests
// on the crests in each quarter. The spread rule's corners stood on texels down the outer ridges'
// flanks, up to 27 um above its support, and the block rested on one point a step, a different
// ridge each step: never at rest, it moved 0.2-3.1 mm in 0.9 s along the grooves (docs/physics.md,
// Known gaps). Up to four, deepest first.
std::size_t selectBoxQuarterContacts(std::span<const ReliefCandidate> candidates, const Eigen::Vector2d& centre_xy,
                                     const Eigen::Vector2d& axis_a, const Eigen::Vector2d& axis_b, double prefer_spread,
                                     std::array<std::size_t, kMaxReliefContacts>& chosen);

// Whether a point that walked from `start` to `bottom` may take that basin under
// BasinClaim::NearestPoint: `others` are the other chosen points where they are. The box's
// row-by-row path (box_relief_contacts.cpp) and snapToBasins decide with this one function.
bool nearestClaims(const Eigen::Vector2d& start, const Eigen::Vector2d& bottom, std::span<const Eigen::Vector2d> others);

}  // namespace thx::phys
