// A ball in a relief of its own curvature gets its contacts by position (conforming_contact.hpp):
// where the relief conforms, four texels at the widest ring the cap offers, each measured as the
// ball's gap from the texel's tangent plane; elsewhere, or where the ball touches the relief
// deeper than at that ring, nothing (the usual rule applies).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>

#include "clients/physics/conforming_contact.hpp"
#include "physics_fixtures.hpp"

namespace thx::phys::test::test_conforming_contact {
namespace {

constexpr double kBall = 0.005;   // m, the ball's radius and the cap's
constexpr double kRim = 0.004;    // m, the dimple's rim radius
constexpr double kDepth = 0.002;  // m
constexpr double kCapCentreZ = kBall - kDepth;  // the cap's centre above the plane (3 mm)

double capOf(double cap, double x, double y) {
  const double r2 = x * x + y * y;
  return r2 < kRim * kRim ? -(std::sqrt(cap * cap - r2) - std::sqrt(cap * cap - kRim * kRim)) : 0.0;
}
double conformingCap(double x, double y) { return capOf(kBall, x, y); }
double widerCap(double x, double y) { return capOf(2.0 * kBall, x, y); }

struct Picked {
  std::size_t n = 0;
  std::vector<ReliefCandidate> contacts;
};

Picked pick(const tex::TexturedSurface& surface, const Eigen::Vector3d& centre,
            std::vector<ReliefCandidate> candidates = {}) {
  std::array<std::size_t, kMaxReliefContacts> chosen{};
  Picked p;
  p.n = selectConformingContacts(surface, Underside::sphere(at(centre.x(), centre.y(), centre.z()), kBall), candidates, chosen);
  for (std::size_t k = 0; k < p.n; ++k) p.contacts.push_back(candidates[chosen[k]]);
  return p;
}

std::set<std::pair<long long, long long>> texelsOf(const Picked& p) {
  std::set<std::pair<long long, long long>> s;
  for (const ReliefCandidate& c : p.contacts) s.insert({c.i, c.j});
  return s;
}

TEST(ConformingContact, FourTexelsAtTheCapsWidestRingMeasuredOnTheirTangentPlanes) {
  const SurfaceHolder s = holdSurface(heightMap(256, 0.1, conformingCap), 0.1, true);
  const double texel = s.surface.texelSize();
  const Eigen::Vector3d cap_centre(0.0, 0.0, kCapCentreZ);
  const Eigen::Vector3d centre = cap_centre + Eigen::Vector3d(0.3 * texel, 0.2 * texel, -1e-6);
  const Picked p = pick(s.surface, centre);
  ASSERT_EQ(p.n, 4u);
  for (std::size_t k = 0; k < p.n; ++k) {
    const ReliefCandidate& c = p.contacts[k];
    const double radius = c.p_surface.head<2>().norm();
    // On the cap with both neighbours (its normal's stencil inside the rim), at most two texels in.
    EXPECT_LT(radius, kRim - texel) << k;
    EXPECT_GT(radius, kRim - 2.0 * texel) << k;
    // The gap from the tangent plane of an exact cap is the ball's offset along the normal.
    EXPECT_NEAR(c.depth, (centre - cap_centre).dot(c.n_local), 0.1e-6) << k;
    if (k > 0) {
      EXPECT_LE(p.contacts[k - 1].depth, c.depth);  // deepest first
    }
  }
  // The same four texels for a ball that moves by micrometres (rocking at rest).
  EXPECT_EQ(texelsOf(pick(s.surface, centre + Eigen::Vector3d(2e-6, -2e-6, 2e-6))), texelsOf(p));
}

TEST(ConformingContact, NoneWhereTheReliefDoesNotConform) {
  const SurfaceHolder cap = holdSurface(heightMap(256, 0.1, conformingCap), 0.1, true);
  const double texel = cap.surface.texelSize();
  // Near the rim: the walk towards it ends within kConformMinWalk texels.
  EXPECT_EQ(pick(cap.surface, {kRim - 2.0 * texel, 0.0, kCapCentreZ}).n, 0u);
  // A flat relief, and a cap of twice the ball's radius: the relief's curvature is not the ball's.
  const SurfaceHolder flat = holdSurface(flatRelief(256), 0.1, true);
  EXPECT_EQ(pick(flat.surface, {0.0, 0.0, kBall}).n, 0u);
  const SurfaceHolder wider = holdSurface(heightMap(256, 0.1, widerCap), 0.1, true);
  EXPECT_EQ(pick(wider.surface, {0.0, 0.0, kBall + widerCap(0.0, 0.0)}).n, 0u);  // resting on its bottom
  // A conforming cap, but the ball touches elsewhere, 0.1 mm deeper than at the ring (a ball
  // crossing the cap fast meets its far wall): the usual rule.
  const Eigen::Vector3d centre(0.0, 0.0, kCapCentreZ);
  ReliefCandidate wall;
  wall.depth = -1e-4;
  EXPECT_EQ(pick(cap.surface, centre, {wall}).n, 0u);
  wall.depth = -1e-6;  // within the tolerance: a resting ball's rim texels
  EXPECT_EQ(pick(cap.surface, centre, {wall}).n, 4u);
}

}  // namespace
}  // namespace thx::phys::test::test_conforming_contact
