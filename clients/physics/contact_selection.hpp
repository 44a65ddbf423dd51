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
void snapToBasins(std::span<const ReliefCandidate> candidates, long long stride_i, long long stride_j,
                  std::span<std::size_t> chosen);

}  // namespace thx::phys
