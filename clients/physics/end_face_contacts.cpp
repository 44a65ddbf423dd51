#include "clients/physics/end_face_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thx::phys {

namespace {

// A face tilted less than about this (radians) has no fall line of its own but the rounding's; its
// rim points then follow the cylinder's own radial axis instead, blended in continuously so that
// the points never jump between the two.
constexpr double kLevelTilt = 1e-3;

// The candidate whose texel centre lies nearest `target` in the plane; candidates.size() if none
// lies within `reach`.
std::size_t nearestTo(std::span<const ReliefCandidate> candidates, const Eigen::Vector2d& target, double reach) {
  std::size_t best = candidates.size();
  double best_d2 = reach * reach;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const double d2 = (candidates[k].p_surface.head<2>() - target).squaredNorm();
    if (d2 <= best_d2) best_d2 = d2, best = k;
  }
  return best;
}

}  // namespace

bool standsOnEndFace(const Underside& shape) {
  return shape.kind == Underside::Kind::Cylinder &&
         std::fabs(shape.plane_from_object.linear()(2, shape.axis)) >= std::sqrt(0.5);
}

std::size_t selectEndFaceContacts(std::span<const ReliefCandidate> candidates, const Underside& cylinder, double texel_m,
                                  long long stride_i, long long stride_j,
                                  std::array<std::size_t, kMaxReliefContacts>& chosen) {
  if (candidates.empty()) return 0;
  const Eigen::Matrix3d& r = cylinder.plane_from_object.linear();
  const Eigen::Vector3d axis = r.col(cylinder.axis);
  // The lower end face: its centre, and the face's steepest way down within its plane.
  const Eigen::Vector3d down_axis = axis.z() > 0.0 ? Eigen::Vector3d(-axis) : axis;
  const Eigen::Vector3d centre = cylinder.plane_from_object.translation() + cylinder.half_length * down_axis;
  const Eigen::Vector3d fall = -Eigen::Vector3d::UnitZ() + down_axis * down_axis.z();  // |fall| = sin(tilt)
  const Eigen::Vector3d own = r.col((cylinder.axis + 1) % 3);                        // in the face's plane
  const Eigen::Vector3d along = (fall + kLevelTilt * own).normalized();
  const double reach = std::max(cylinder.radius - texel_m, 0.0);

  std::size_t rim[2];
  int found = 0;
  for (double side : {1.0, -1.0}) {
    const Eigen::Vector3d p = centre + side * reach * along;
    const std::size_t k = nearestTo(candidates, p.head<2>(), texel_m);
    if (k < candidates.size() && (found == 0 || k != rim[0])) rim[found++] = k;
  }
  std::size_t deepest = 0;
  for (std::size_t k = 1; k < candidates.size(); ++k)
    if (candidates[k].depth < candidates[deepest].depth) deepest = k;

  double deepest_rim = std::numeric_limits<double>::infinity();
  for (int i = 0; i < found; ++i) deepest_rim = std::min(deepest_rim, candidates[rim[i]].depth);
  std::size_t n = 0;
  // The deepest texel too where the face is tipped against the relief, or where no rim point was
  // found.
  if (found == 0 || candidates[deepest].depth < deepest_rim - kEndFaceTipM) chosen[n++] = deepest;
  for (int i = 0; i < found; ++i)
    if (n == 0 || rim[i] != chosen[0]) chosen[n++] = rim[i];
  // A rim point clear of the relief (a bumpy relief under a level face) goes to the bottom of its
  // basin in depth, the top of the bump under the face nearest it, if that is nearer to it than to
  // every other point (BasinClaim::NearestPoint). A rim point that touches stays: on a slope the
  // basins are the depths' rounding, and walking them gathered the points.
  const double touching = candidates[deepest].depth + kEndFaceClearM;
  for (std::size_t c = 0; c < n; ++c) {
    if (!(candidates[chosen[c]].depth > touching)) continue;
    std::array<std::size_t, 1> walk{chosen[c]};
    snapToBasins(candidates, stride_i, stride_j, walk);
    std::array<Eigen::Vector2d, kMaxReliefContacts> others;
    std::size_t n_others = 0;
    for (std::size_t e = 0; e < n; ++e)
      if (e != c) others[n_others++] = candidates[chosen[e]].p_surface.head<2>();
    if (nearestClaims(candidates[chosen[c]].p_surface.head<2>(), candidates[walk[0]].p_surface.head<2>(),
                      std::span(others.data(), n_others)))
      chosen[c] = walk[0];
  }
  // Deepest first, as addReliefContacts takes them (relief_collision.cpp: of two points within the
  // breaking threshold of each other the deeper must win) and the caller refines the first.
  std::sort(chosen.begin(), chosen.begin() + std::ptrdiff_t(n),
            [&](std::size_t a, std::size_t b) { return candidates[a].depth < candidates[b].depth; });
  return n;
}

}  // namespace thx::phys
