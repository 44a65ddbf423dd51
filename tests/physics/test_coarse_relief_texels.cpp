// A plain ball or a box on relief texels coarse against it (docs/physics.md, "Relief texels coarse
// against a ball"): where no texel centre lies within the threshold under it, it still meets the
// relief between them (deepestBetweenTexelCentres and boxCornerContacts,
// relief_raster.hpp), at rest and rolling. Before, a 5 mm ball set between four centres of
// 1.95 mm texels sank 25 um and rattled at 4.9 mm/s, where no centre lay within its radius
// (7.81 mm texels) it fell in and was thrown out, and a box smaller than the texels fell through
// or stood on one centre by its corner.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "physics_fixtures.hpp"

namespace thx::phys::test::test_coarse_relief_texels {
namespace {

constexpr double kDt = 1e-3;
constexpr double kRadius = 0.005, kMass = 0.01, kExtent = 0.5;
const BodyMaterial kPlane{0.5, 0.0, 0.0};
// Texels of 1.95, 3.91 and 7.81 mm over the half-metre plane: 0.39, 0.78 and 1.56 of the radius.
constexpr int kCoarseTexels[] = {256, 128, 64};

PhysicsWorld awakeWorld() {
  WorldOptions options;
  options.rest.enabled = false;  // every step is seen
  return PhysicsWorld(options);
}

TEST(CoarseReliefTexels, ABallSetBetweenTexelCentresRestsOnTheFlatRelief) {
  for (const int texels : kCoarseTexels) {
    const double d = kExtent / texels;
    const SurfaceHolder plane = holdSurface(flatRelief(texels), kExtent, true);
    // On a texel's corner, on the middle of its edge, and off both (offsets in texels).
    for (const auto& [ox, oy] : {std::pair{1.0, 1.0}, std::pair{1.0, 0.5}, std::pair{0.8, 0.9}}) {
      SCOPED_TRACE(::testing::Message() << d * 1e3 << " mm texels, at (" << ox << ", " << oy << ")");
      PhysicsWorld world = awakeWorld();
      world.addReliefPlane(plane.surface, kPlane);
      const double x = (100 + ox) * d - 0.5 * kExtent, y = (100 + oy) * d - 0.5 * kExtent;
      btRigidBody& ball = world.addSphere(kRadius, kMass, at(x, y, kRadius + 1e-4), {0.5, 0.0, 0.0});
      double fastest = 0.0;
      for (int k = 0; k < 2000; ++k) {
        world.step(kDt);
        if (k >= 1000) fastest = std::max(fastest, velocityOf(ball).norm());
      }
      EXPECT_NEAR(positionOf(ball).z(), kRadius, 1e-7);  // on the relief, not between its centres
      EXPECT_LT(fastest, 1e-6);                          // still over the second second
      EXPECT_NEAR(positionOf(ball).x(), x, 1e-6);
      EXPECT_NEAR(positionOf(ball).y(), y, 1e-6);
    }
  }
}

TEST(CoarseReliefTexels, ABallRollingAcrossCoarseTexelsKeepsItsHeightAndSpeed) {
  for (const int texels : kCoarseTexels) {
    const SurfaceHolder plane = holdSurface(flatRelief(texels), kExtent, true);
    for (int run = 0; run < 8; ++run) {
      const double heading = 0.3 + 0.7 * run;  // eight headings across the texel grid
      SCOPED_TRACE(::testing::Message() << kExtent / texels * 1e3 << " mm texels, heading " << heading << " rad");
      PhysicsWorld world = awakeWorld();
      world.addReliefPlane(plane.surface, kPlane);
      btRigidBody& ball = world.addSphere(kRadius, kMass, at(-0.05 + 0.0013 * run, 0.0031 * run, kRadius), {0.5, 0.0, 0.0});
      // Rolling without slipping at 0.1 m/s from the start.
      const Eigen::Vector3d v(0.1 * std::cos(heading), 0.1 * std::sin(heading), 0.0);
      ball.setLinearVelocity(btVector3(float(v.x()), float(v.y()), 0.0f));
      ball.setAngularVelocity(btVector3(float(-v.y() / kRadius), float(v.x() / kRadius), 0.0f));
      double lowest = kRadius, highest = kRadius;
      for (int k = 0; k < 1000; ++k) {
        world.step(kDt);
        lowest = std::min(lowest, positionOf(ball).z());
        highest = std::max(highest, positionOf(ball).z());
      }
      EXPECT_NEAR(lowest, kRadius, 1e-7);
      EXPECT_NEAR(highest, kRadius, 1e-7);
      EXPECT_NEAR(velocityOf(ball).norm(), 0.1, 1e-5);  // float-stored 0.1 m/s, kept
    }
  }
}

TEST(CoarseReliefTexels, ABallRollsDownACoarseRampAsDownAFineOne) {
  // A 5 degree ramp of 0.2 m (the texture generator's tilted relief, depth 0 at the first texel's
  // centre): a 1 cm ball at 5/7 g sin cos along x, from 0.39 mm texels to 12.5 mm (1.25 radii).
  const double angle = deg(5.0), extent = 0.2, r = 0.01;
  const double expected = 5.0 / 7.0 * kG * std::sin(angle) * std::cos(angle);
  for (const int texels : {512, 32, 16}) {
    SCOPED_TRACE(::testing::Message() << extent / texels * 1e3 << " mm texels");
    const SurfaceHolder ramp = holdSurface(tiltedMap(5.0, texels, extent), extent, true);
    auto surfaceZ = [&](double x) { return -std::tan(angle) * (x + 0.5 * extent - 0.5 * extent / texels); };
    PhysicsWorld world = awakeWorld();
    world.addReliefPlane(ramp.surface, kPlane);
    const double x0 = -0.08;
    btRigidBody& ball = world.addSphere(r, 0.05, at(x0, 0.0013, surfaceZ(x0) + r / std::cos(angle)), {0.5, 0.0, 0.0});
    double v1 = 0.0, farthest_off = 0.0;
    for (int k = 1; k <= 300; ++k) {
      world.step(kDt);
      if (k == 100) v1 = velocityOf(ball).x();
      const Eigen::Vector3d p = positionOf(ball);
      if (k >= 20) farthest_off = std::max(farthest_off, std::fabs((p.z() - surfaceZ(p.x())) * std::cos(angle) - r));
    }
    EXPECT_NEAR((velocityOf(ball).x() - v1) / 0.2, expected, 0.01 * expected);
    EXPECT_LT(farthest_off, 2e-5);  // on the ramp along its normal
  }
}

TEST(CoarseReliefTexels, ABoxLessThanTwoTexelsAcrossRestsOnTheFlatRelief) {
  // An 8 mm box on texels of 7.81, 12.5 and 25 mm, its footprint between the centres (before: no
  // contact, it fell through the relief), over one by its corner (before: 2.7 mm low) or over one
  // under its middle.
  const double h = 0.004;
  for (const int texels : {64, 40, 20}) {
    const double d = kExtent / texels;
    const SurfaceHolder plane = holdSurface(flatRelief(texels), kExtent, true);
    for (const double o : {0.9, 0.5}) {
      SCOPED_TRACE(::testing::Message() << d * 1e3 << " mm texels, at " << o << " of a texel");
      PhysicsWorld world = awakeWorld();
      world.addReliefPlane(plane.surface, kPlane);
      const double x = (100 + o) * d - 0.5 * kExtent;
      btRigidBody& box = world.addBox({h, h, h}, 0.005, at(x, x, h + 1e-4), {0.5, 0.0, 0.0});
      double fastest = 0.0;
      for (int k = 0; k < 2000; ++k) {
        world.step(kDt);
        if (k >= 1000) fastest = std::max(fastest, velocityOf(box).norm());
      }
      EXPECT_NEAR(positionOf(box).z(), h, 1e-7);
      EXPECT_LT(fastest, 2e-5);
    }
  }
}

}  // namespace
}  // namespace thx::phys::test::test_coarse_relief_texels
