#include "clients/physics/conforming_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace thx::phys {

std::size_t selectConformingContacts(const tex::TexturedSurface& surface, const Underside& ball,
                                     std::vector<ReliefCandidate>& candidates,
                                     std::array<std::size_t, kMaxReliefContacts>& chosen) {
  const Eigen::Vector3d centre = ball.plane_from_object.translation();
  long long i0 = 0, j0 = 0;
  surface.texelContaining(centre.x(), centre.y(), i0, j0);
  // Vertical depth at a texel centre; NaN where the ball is not above it (a NaN fails every test).
  auto depthAt = [&](long long i, long long j) {
    const tex::TexelPoint t = surface.texelPoint(i, j);
    const std::optional<double> z = lowestZ(ball, t.q_local.x(), t.q_local.y());
    return z ? *z - t.q_local.z() : std::nan("");
  };
  const double texel = surface.texelSize();
  const double tolerance = kConformFraction * texel * texel / ball.radius;
  // No walk goes farther than the ball's radius.
  const long long longest = std::max(kConformMinWalk, (long long)std::floor(ball.radius / texel));
  constexpr std::array<std::array<long long, 2>, kMaxReliefContacts> kDirections = {{{1, 0}, {0, -1}, {-1, 0}, {0, 1}}};
  std::array<long long, kMaxReliefContacts> walked{};
  for (std::size_t d = 0; d < kDirections.size(); ++d) {
    const long long di = kDirections[d][0], dj = kDirections[d][1];
    double before = depthAt(i0 - di, j0 - dj), here = depthAt(i0, j0);
    long long k = 0;
    for (; k <= longest; ++k) {
      const double after = depthAt(i0 + (k + 1) * di, j0 + (k + 1) * dj);
      if (!(std::fabs(before + after - 2.0 * here) < tolerance)) break;
      before = here, here = after;
    }
    // k: the first texel along the walk that does not keep the curvature; the one before is the
    // last that does (its neighbours, and so its normal, lie on the cap).
    if (k - 1 < kConformMinWalk) return 0;
    walked[d] = k - 1;
  }
  // The ring must be where the ball touches: no candidate may lie deeper (vertically) than the
  // ring's deepest texel by more than the tolerance, or, when the ring itself is penetrated, by
  // more than that penetration again (a ball sunk into the cap and off its centre, at 60 Hz, is
  // deeper towards the rim than at the ring). A ball crossing a cap fast touches its far wall,
  // not the ring: four ring points let it sink into that wall, and the usual rule, taking over
  // a step later, threw it out (measured in dimple_ball: one-step energy gains of up to 10 % of
  // its launch energy, its path changed; with this test both are the usual rule's).
  double ring_depth = std::numeric_limits<double>::infinity();
  for (std::size_t d = 0; d < kDirections.size(); ++d)
    ring_depth = std::min(ring_depth, depthAt(i0 + walked[d] * kDirections[d][0], j0 + walked[d] * kDirections[d][1]));
  const double allowed = ring_depth - tolerance - std::max(0.0, -ring_depth);
  for (const ReliefCandidate& c : candidates)
    if (c.depth < allowed) return 0;
  for (std::size_t d = 0; d < kDirections.size(); ++d) {
    const long long i = i0 + walked[d] * kDirections[d][0], j = j0 + walked[d] * kDirections[d][1];
    const tex::TexelPoint t = surface.texelPoint(i, j);
    ReliefCandidate c;
    c.p_surface = t.q_local;
    c.n_local = t.n_local;
    c.depth = (centre - t.q_local).dot(t.n_local) - ball.radius;
    c.i = i, c.j = j;
    chosen[d] = candidates.size();
    candidates.push_back(c);
  }
  // Deepest first, as the manifold expects (relief_collision.cpp skips later coincident points).
  std::sort(chosen.begin(), chosen.end(),
            [&](std::size_t a, std::size_t b) { return candidates[a].depth < candidates[b].depth; });
  return kMaxReliefContacts;
}

}  // namespace thx::phys
