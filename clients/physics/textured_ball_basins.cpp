#include "clients/physics/textured_ball_basins.hpp"

#include <algorithm>
#include <cmath>

namespace thx::phys {

BallBasins findBallBasins(const tex::TexturedSurface& surface, const Underside& ball, const FaceTexture& texture,
                          double threshold_m, double closing_within_m, const GroundBend* bend,
                          const ChartBoundary* boundary, BallBasinHint& hint, std::vector<ReliefCandidate>& candidates) {
  const Eigen::Vector3d centre = ball.plane_from_object.translation();
  // Where the basins' depths are measured from; a guess, not a bound (the check below is what
  // makes the result exact).
  const double lowest = centre.z() - ball.radius - (bend ? bend->height(centre.x(), centre.y()) : 0.0);
  BallBasins b;
  std::size_t found = 0;
  auto read = [&](double within) {
    candidates.clear();
    b.raster = rasterizeRelief(surface, ball, threshold_m, candidates, &texture, bend, false, boundary, within);
    ++b.passes;
    dropPastBoundary(boundary, candidates);
    found = selectShallowestBasins(candidates, b.raster.stride_i, b.raster.stride_j, b.picked);
    b.count = std::min(found, kMaxReliefContacts);
    while (b.count < found && candidates[b.picked[b.count]].depth < closing_within_m) ++b.count;
  };
  auto fourthDepth = [&] { return candidates[b.picked[kMaxReliefContacts - 1]].depth; };
  if (std::isfinite(hint.reach_m)) {
    const double bound = firstReadBound(hint, lowest, threshold_m, closing_within_m);
    if (bound < threshold_m) {
      read(bound);
      if (found >= kMaxReliefContacts && fourthDepth() < bound) {
        hint.reach_m = fourthDepth() - lowest;
        return b;
      }
    }
  }
  read(threshold_m);
  b.whole_disc = true;
  hint.reach_m = found >= kMaxReliefContacts ? fourthDepth() - lowest : std::numeric_limits<double>::quiet_NaN();
  return b;
}

}  // namespace thx::phys
