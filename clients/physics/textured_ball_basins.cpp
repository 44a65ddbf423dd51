#include "clients/physics/textured_ball_basins.hpp"

#include <algorithm>
#include <cmath>

namespace thx::phys {

BallBasins findBallBasins(const tex::TexturedSurface& surface, const Underside& ball, const FaceTexture& texture,
                          double threshold_m, const GroundBend* bend, const ChartBoundary* boundary, BallBasinHint& hint,
                          std::vector<ReliefCandidate>& candidates) {
  const Eigen::Vector3d centre = ball.plane_from_object.translation();
  // Where the basins' depths are measured from; a guess, not a bound (the check below is what
  // makes the result exact).
  const double lowest = centre.z() - ball.radius - (bend ? bend->height(centre.x(), centre.y()) : 0.0);
  BallBasins b;
  auto read = [&](double within) {
    candidates.clear();
    b.raster = rasterizeRelief(surface, ball, threshold_m, candidates, &texture, bend, false, boundary, within);
    ++b.passes;
    dropPastBoundary(boundary, candidates);
    b.count = selectShallowestBasins(candidates, b.raster.stride_i, b.raster.stride_j, b.picked);
  };
  auto fourthDepth = [&] { return candidates[b.picked[kMaxReliefContacts - 1]].depth; };
  if (std::isfinite(hint.reach_m)) {
    const double bound = lowest + kBallBasinReachGrowth * std::max(0.0, hint.reach_m) + kBallBasinReachMargin * threshold_m;
    if (bound < threshold_m) {
      read(bound);
      if (b.count == kMaxReliefContacts && fourthDepth() < bound) {
        hint.reach_m = fourthDepth() - lowest;
        return b;
      }
    }
  }
  read(threshold_m);
  b.whole_disc = true;
  hint.reach_m = b.count == kMaxReliefContacts ? fourthDepth() - lowest : std::numeric_limits<double>::quiet_NaN();
  return b;
}

}  // namespace thx::phys
