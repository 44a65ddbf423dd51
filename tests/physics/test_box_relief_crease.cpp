// A plain box against creases of a relief (issue 29, crease_contact.hpp): resting flat on bricks
// it is pushed along its face's normal at the bricks' edges, where the relief's normals lean 31°
// into the joints; pushed against a kerb it is held back, not lifted onto it, as before the rule
// (the floor's texels beside the kerb lean away from it).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "clients/physics/bullet_convert.hpp"
#include "physics_fixtures.hpp"

namespace thx::phys::test::test_box_relief_crease {
namespace {

constexpr double kDt = 1e-3, kMass = 0.05, kExtent = 0.125;

struct BoxOnRelief : ReliefWorld {
  btRigidBody* box = nullptr;

  BoxOnRelief(int texels, const std::function<double(double, double)>& height, const Eigen::Vector3d& centre,
              double half, double friction)
      : ReliefWorld(height, kExtent, texels, tex::Address::Wrap) {
    box = &world->addBox(Eigen::Vector3d::Constant(half), kMass, at(centre.x(), centre.y(), centre.z()), {friction, 0.0, 0.0});
  }
  void run(double seconds, const Eigen::Vector3d& force_over_weight = Eigen::Vector3d::Zero()) {
    for (int k = 0; k < int(std::lround(seconds / kDt)); ++k) {
      box->activate(true);
      box->applyCentralForce(toBt(Eigen::Vector3d(force_over_weight * kMass * kG)));
      world->step(kDt);
    }
  }
};

// Bricks 12 x 6 mm, 1 mm joints 0.6 mm deep; the brick tops at z = 0.
double bricks(double x, double y) {
  x += 1.0, y += 1.0;  // positive, for fmod
  return std::fmod(x, 0.012) < 0.001 || std::fmod(y, 0.006) < 0.001 ? -6e-4 : 0.0;
}

TEST(BoxOnAReliefCrease, ABoxRestingFlatOnBricksStaysPut) {
  // Without the crease rule: 0.73 mm (256 texels) and 0.19 mm (512) in this second, at up to
  // 3.2 and 5.5 mm/s.
  for (int texels : {256, 512}) {
    BoxOnRelief s(texels, bricks, {0.013, 0.007, 0.01 + 1e-5}, 0.01, 0.5);
    s.run(0.3);
    const Eigen::Vector3d start = positionOf(*s.box);
    double fastest = 0.0;
    for (int k = 0; k < 10; ++k) {
      s.run(0.1);
      fastest = std::max(fastest, velocityOf(*s.box).norm());
    }
    const double moved = (positionOf(*s.box) - start).norm();
    std::printf("[measured] %d texels: moved %.3g mm in 1 s, fastest %.3g mm/s\n", texels, 1e3 * moved, 1e3 * fastest);
    EXPECT_LT(moved, 0.01e-3) << texels << " texels";
    EXPECT_LT(fastest, 0.05e-3) << texels << " texels";
  }
}

TEST(BoxOnAReliefCrease, ABoxPushedAgainstAKerbIsHeldBackNotLiftedOntoIt) {
  // A 3 mm kerb from x = 5 mm on; a 1 cm box on the floor pushed against it at half its weight
  // (friction 0.3 lets it slide): it stops at the kerb and stays on the floor, as it did before
  // the crease rule (the floor's texels beside the kerb lean away from it; the kerb's top edge
  // is a crease, but the box is not resting on it).
  auto kerb = [](double x, double) { return x > 0.005 ? 0.0 : -0.003; };
  BoxOnRelief s(256, kerb, {-0.005, 0.0, -0.003 + 0.005 + 1e-5}, 0.005, 0.3);
  s.run(0.2);
  s.run(1.0, {0.5, 0.0, 0.0});
  const Eigen::Vector3d p = positionOf(*s.box);
  std::printf("[measured] the box's centre at x %.3f mm (its face at %.3f mm), z %.3f mm over the floor\n", 1e3 * p.x(),
              1e3 * (p.x() + 0.005), 1e3 * (p.z() + 0.003));
  EXPECT_LT(p.x() + 0.005, 0.0055);           // at the kerb (within a texel), not over it
  EXPECT_NEAR(p.z() + 0.003, 0.005, 0.1e-3);  // on the floor
}

}  // namespace
}  // namespace thx::phys::test::test_box_relief_crease
