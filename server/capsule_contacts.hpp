#pragma once
// Where a capsule (the stylus: a segment swept by a ball) meets a textured plane, read from the
// texture as the point pen reads it (docs/design.md §5): a relief map is geometry, a normal map is
// the flat plane with its sampled normals. Used by the pen with extent (capsule_tool.hpp).
//
//  - relief: the surface is the texel centres' points (x, y, -depth). Where a texel centre is
//    within the radius plus a margin of the axis and no 8-neighbour nearest to the same part of the
//    capsule (tip ball, shaft, back ball) is nearer, the texel's plane (its centre, its own normal,
//    as the point pen's plane proxies) is a contact, its gap measured from the capsule's nearest
//    axis point: one contact per feature (a crest under the shaft, each wall of a valley under
//    the ball, each end of a shaft lying flat). Between texel centres the capsule can dip by at
//    most texel² / (8 radius), 1.6 µm for a 0.1 mm texel under a 1 mm ball.
//  - normal map: under the shaft's line (in x and y), the plane through the surface point
//    (x, y, 0) with the sampled normal, as the point pen's plane proxy (Eq. 3), its gap measured
//    from the axis point above it; kept: the two ends of the part within reach and every sample
//    nearer than its neighbours.
// Plane-local coordinates throughout (the surface's frame: z out of the plane).
//
// Real-time safe: fixed-size output, no allocation. Cost grows with the texels the shaft's lower
// part covers within reach of the surface, nine reads for each within reach
// (benchmarks/bench_capsule_tool.cpp); contacts beyond kMaxToolContacts keep the nearest.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "textures/textured_surface.hpp"

namespace thx::srv {

inline constexpr int kMaxToolContacts = 64;

struct ToolContact {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();        // on the surface, where the force acts
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();      // unit, out of the surface into the tool
  double gap_m = 0.0;  // distance from the surface to the capsule along the normal (< 0: inside)
  // A relief's texel the contact stands for (unwrapped indices), so the tool can carry it into the
  // next pass (addCarriedContact()); none on a normal map.
  bool has_texel = false;
  long long texel_i = 0, texel_j = 0;
};

struct ToolContacts {
  std::array<ToolContact, kMaxToolContacts> c{};
  int count = 0;
  int texels_examined = 0;  // the search's cost
  // The nearest any texel examined came to the capsule (gap, m; +inf when none was within the
  // margin's region): how far the tool can move before anything it did not look at matters.
  double nearest_gap_m = 0.0;
  bool overflow = false;    // more candidates than kMaxToolContacts (the nearest were kept)
};

// The stylus: a ball of `radius_m` swept from `a` (the tip's ball centre) to `b`.
struct CapsuleShape {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::UnitZ();
  double radius_m = 0.0;
};

// The relief's highest point in each block of kBlock x kBlock texels, so that a search skips the
// blocks the capsule cannot reach (a shaft lying across valleys reads their crests only). Built off
// the servo thread (it allocates); empty (no skipping) for a normal map or a map whose sides are
// not multiples of kBlock.
class ReliefBlockHeights {
 public:
  static constexpr int kBlock = 8;
  ReliefBlockHeights() = default;
  explicit ReliefBlockHeights(const tex::TexturedSurface& surface);
  bool empty() const { return top_m_.empty(); }
  // The highest surface z (plane frame) over the unwrapped texels [kBlock bi, kBlock bi + kBlock) x
  // [kBlock bj, ...).
  double top(const tex::TexturedSurface& surface, long long bi, long long bj) const;

 private:
  int blocks_x_ = 0;
  std::vector<float> top_m_;
};

// Every contact whose gap is below margin_m (the distance the tool may move this tick).
void findCapsuleContacts(const tex::TexturedSurface& surface, const CapsuleShape& capsule, double margin_m,
                         ToolContacts& out, const ReliefBlockHeights* blocks = nullptr);

// Only out.nearest_gap_m (no contacts): how far the capsule is from every texel within margin_m of
// it, one read a texel (the search for contacts reads nine for each texel within its margin).
void findCapsuleClearance(const tex::TexturedSurface& surface, const CapsuleShape& capsule, double margin_m,
                          ToolContacts& out, const ReliefBlockHeights* blocks = nullptr);

// The relief texel (i, j)'s contact with the capsule at its present pose, added to `out` unless a
// contact of that texel is there already. The tool carries the contacts that held in its last
// solve into the next pass this way: a ball in a rounded floor found one contact per feature, the
// nearest texel, and with only that contact's plane it slid across the floor and back, a contact
// a tick, a quarter millimetre each way (the stability map's smoothed 160 degree valleys: 0.2 N
// of ripple); with the last solve's plane kept it rests between the two.
void addCarriedContact(const tex::TexturedSurface& surface, const CapsuleShape& capsule, long long i, long long j,
                       ToolContacts& out);

// The point of segment [a, b] nearest to p, as its parameter in [0, 1].
double nearestOnSegment(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& p);

}  // namespace thx::srv
