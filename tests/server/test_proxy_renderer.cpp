// Plane-proxy rendering on textured planes: spring law, relief contact, crease handling in a
// steep V-valley, the recovery rule, world-frame planes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "server/proxy_renderer.hpp"
#include "textures/generators.hpp"

using namespace thx;
using srv::ProxyRenderer;
using srv::RendererConfig;

namespace {

constexpr double kExtent = 0.2;

tex::TextureMap generated(const std::string& kind, std::map<std::string, double> params, int size = 512) {
  tex::GenerateRequest r;
  r.kind = kind;
  r.size = size;
  r.params = std::move(params);
  r.params["extent"] = kExtent;
  return tex::generate(r);
}

tex::PlaneMapping mapping() {
  tex::PlaneMapping m;
  m.size_m = {kExtent, kExtent};
  return m;
}

RendererConfig config(bool crease, int recovery_ticks = 0) {
  RendererConfig c;
  c.stiffness_n_per_m = 1000.0;
  c.damping_ns_per_m = 0.0;
  c.crease_handling = crease;
  c.recovery_ticks = recovery_ticks;
  return c;
}

// vvalley, period 4 mm, 60 deg opening: walls at alpha = 60 deg, depth 3.46 mm; a floor at x = 2 mm.
constexpr double kFloorX = 0.002;
const double kAlpha = 60.0 * std::numbers::pi / 180.0;
const double kValleyDepth = 0.002 * std::tan(kAlpha);

}  // namespace

TEST(ProxyRenderer, FlatNormalMapIsASpringAlongTheNormal) {
  const tex::TextureMap map(8, 8, tex::Representation::Normal);
  const tex::TexturedSurface surface(map, mapping(), {}, false);
  for (bool crease : {false, true}) {
    ProxyRenderer r(surface, config(crease));
    EXPECT_FALSE(r.render({0.01, 0.02, 0.001}, Eigen::Vector3d::Zero()).in_contact);
    const srv::RenderOutput out = r.render({0.01, 0.02, -0.002}, Eigen::Vector3d::Zero());
    ASSERT_TRUE(out.in_contact);
    EXPECT_NEAR(out.force_world.z(), 2.0, 1e-9);  // 1000 N/m x 2 mm
    EXPECT_NEAR(out.force_world.head<2>().norm(), 0.0, 1e-9);
    EXPECT_NEAR(out.depth_m, 0.002, 1e-12);
  }
}

TEST(ProxyRenderer, DampingOpposesApproachButNeverPulls) {
  const tex::TextureMap map(8, 8, tex::Representation::Normal);
  const tex::TexturedSurface surface(map, mapping(), {}, false);
  RendererConfig c = config(false);
  c.damping_ns_per_m = 2.0;
  ProxyRenderer r(surface, c);
  // Moving in at 0.1 m/s: 1 N spring + 0.2 N damper.
  EXPECT_NEAR(r.render({0, 0, -0.001}, {0, 0, -0.1}).force_world.z(), 1.2, 1e-9);
  // Leaving fast: the damper would exceed the spring; the force stops at zero instead of pulling.
  EXPECT_NEAR(r.render({0, 0, -0.001}, {0, 0, 1.0}).force_world.z(), 0.0, 1e-12);
}

TEST(ProxyRenderer, TiltedNormalMapPushesAlongTheSampledNormal) {
  const tex::TextureMap map = generated("tilted", {{"angle_deg", 20.0}}, 64);
  const tex::TexturedSurface surface(map, mapping(), {}, false);  // read as a normal map: flat geometry
  ProxyRenderer r(surface, config(false));
  const srv::RenderOutput out = r.render({0.0, 0.0, -0.001}, Eigen::Vector3d::Zero());
  const Eigen::Vector3d n = out.n_sampled_world;
  EXPECT_NEAR(n.z(), std::cos(20.0 * std::numbers::pi / 180.0), 1e-4);
  EXPECT_LT(out.force_world.normalized().cross(n).norm(), 1e-6);  // along n_s (Eq. 3)
  EXPECT_NEAR(out.force_world.norm(), 1000.0 * 0.001 * n.z(), 1e-6);  // k * penetration along n_s
}

TEST(ProxyRenderer, ReliefContactOnlyBelowTheReliefSurface) {
  const tex::TextureMap map = generated("vvalley", {{"angle_deg", 60.0}, {"period", 0.004}});
  const tex::TexturedSurface surface(map, mapping(), {}, true);
  for (bool crease : {false, true}) {
    ProxyRenderer r(surface, config(crease));
    // 1 mm below the base plane but 1 mm above the valley floor (the floor is 3.46 mm deep).
    EXPECT_FALSE(r.render({kFloorX, 0.0, -(kValleyDepth - 0.001)}, Eigen::Vector3d::Zero()).in_contact);
    const srv::RenderOutput out = r.render({kFloorX + 0.0005, 0.0, -(kValleyDepth + 0.0005)}, Eigen::Vector3d::Zero());
    EXPECT_TRUE(out.in_contact);
    EXPECT_GT(out.relief_depth_m, 0.002);
  }
}

TEST(ProxyRenderer, CreaseHandlingRestsAtTheValleyFloor) {
  const tex::TextureMap map = generated("vvalley", {{"angle_deg", 60.0}, {"period", 0.004}});
  const tex::TexturedSurface surface(map, mapping(), {}, true);
  ProxyRenderer r(surface, config(true));
  // Pressed 1 mm below the floor, directly under it: the proxy sits on the crease, the force is
  // (nearly) straight up: both walls are held, neither pushes the pen sideways.
  srv::RenderOutput out;
  for (int k = 0; k < 5; ++k) out = r.render({kFloorX, 0.0, -kValleyDepth - 0.001}, Eigen::Vector3d::Zero());
  ASSERT_TRUE(out.in_contact);
  EXPECT_GE(out.num_planes, 2);
  EXPECT_NEAR(out.proxy_world.x(), kFloorX, 0.0004);  // within one texel of the true floor
  EXPECT_LT(std::fabs(out.force_world.x()), 0.25 * out.force_world.z());
}

TEST(ProxyRenderer, SweepingAcrossTheFloorJumpsWithOnePlaneAndNotWithCreaseHandling) {
  const tex::TextureMap map = generated("vvalley", {{"angle_deg", 60.0}, {"period", 0.004}});
  const tex::TexturedSurface surface(map, mapping(), {}, true);
  const double z = -kValleyDepth - 0.001, step = 1e-5;  // 10 um per tick
  auto maxLateralStep = [&](bool crease) {
    ProxyRenderer r(surface, config(crease));
    double worst = 0.0, previous = 0.0;
    for (int k = 0; k <= 200; ++k) {
      const double x = kFloorX - 0.001 + k * step;
      const double fx = r.render({x, 0.0, z}, Eigen::Vector3d::Zero()).force_world.x();
      if (k > 0) worst = std::max(worst, std::fabs(fx - previous));
      previous = fx;
    }
    return worst;
  };
  const double single = maxLateralStep(false), crease = maxLateralStep(true);
  // One plane: the normal flips across the floor texel (bilinear blending spreads the flip over
  // one 0.39 mm texel), so the lateral force changes several times faster than the wall spring:
  // an effective lateral stiffness of several k. Crease handling holds both walls: the proxy
  // stays on the floor line and the lateral force is exactly the spring, k * step per step.
  EXPECT_GT(single, 3.0 * 1000.0 * step);
  EXPECT_LT(crease, 1.01 * 1000.0 * step);
}

TEST(ProxyRenderer, RecoveryRuleRampsAPlaneChangeInsteadOfStepping) {
  const tex::TextureMap map = generated("vvalley", {{"angle_deg", 60.0}, {"period", 0.004}});
  const tex::TexturedSurface surface(map, mapping(), {}, true);
  const int ticks = 10;
  ProxyRenderer r(surface, config(false, ticks));
  const double z = -kValleyDepth - 0.001;
  // Sit left of the floor, then step across it in one tick (the plane flips).
  srv::RenderOutput before;
  for (int k = 0; k < 3; ++k) before = r.render({kFloorX - 0.0003, 0.0, z}, Eigen::Vector3d::Zero());
  const srv::RenderOutput first = r.render({kFloorX + 0.0003, 0.0, z}, Eigen::Vector3d::Zero());
  EXPECT_TRUE(first.recovering);
  EXPECT_NEAR(first.force_world.x(), before.force_world.x(), 1e-9);  // keeps the current penetration
  srv::RenderOutput out = first;
  double previous = first.force_world.x();
  double largest_step = 0.0;
  for (int k = 0; k < ticks + 2; ++k) {
    out = r.render({kFloorX + 0.0003, 0.0, z}, Eigen::Vector3d::Zero());
    largest_step = std::max(largest_step, std::fabs(out.force_world.x() - previous));
    previous = out.force_world.x();
  }
  EXPECT_FALSE(out.recovering);
  const double total = std::fabs(out.force_world.x() - before.force_world.x());
  EXPECT_GT(total, 1.0);                                // the plane really changed
  EXPECT_LT(largest_step, total / ticks * 1.01 + 1e-9);  // in equal steps over the ramp
}

// The paper's loop (server/paper_loop.hpp): the plane of a frame is held for plane_hold_ticks,
// so a tip stepping across the floor keeps the old wall's normal until the next frame, and then
// the force steps at once (no recovery rule).
TEST(ProxyRenderer, PaperLoopHoldsOnePlanePerFrame) {
  const tex::TextureMap map = generated("vvalley", {{"angle_deg", 60.0}, {"period", 0.004}});
  const tex::TexturedSurface surface(map, mapping(), {}, true);
  RendererConfig c = config(false);
  c.plane_hold_ticks = 10;
  ProxyRenderer r(surface, c);
  const double z = -kValleyDepth - 0.001;
  const srv::RenderOutput left = r.render({kFloorX - 0.0003, 0.0, z}, Eigen::Vector3d::Zero());  // frame 1
  ASSERT_TRUE(left.in_contact);
  EXPECT_GT(left.force_world.x(), 0.5);  // the left wall pushes right
  for (int k = 1; k < 10; ++k) {         // across the floor within the frame: the same plane
    const srv::RenderOutput out = r.render({kFloorX + 0.0003, 0.0, z}, Eigen::Vector3d::Zero());
    ASSERT_TRUE(out.in_contact) << k;
    EXPECT_NEAR(out.planes[0].n_world.x(), left.planes[0].n_world.x(), 1e-12) << k;
    EXPECT_GT(out.force_world.x(), 0.0) << k;  // still the left wall pushing, less deep across the floor
    EXPECT_NEAR(out.force_world.normalized().dot(left.force_world.normalized()), 1.0, 1e-12) << k;
    EXPECT_FALSE(out.recovering);
  }
  const srv::RenderOutput next = r.render({kFloorX + 0.0003, 0.0, z}, Eigen::Vector3d::Zero());  // frame 2
  EXPECT_LT(next.force_world.x(), -0.5);  // the right wall's plane, at once
  // Every tick re-plans with plane_hold_ticks = 1, as before.
  ProxyRenderer every(surface, config(false));
  every.render({kFloorX - 0.0003, 0.0, z}, Eigen::Vector3d::Zero());
  EXPECT_LT(every.render({kFloorX + 0.0003, 0.0, z}, Eigen::Vector3d::Zero()).force_world.x(), -0.5);
}

TEST(ProxyRenderer, PlanesAreReportedInTheWorldFrame) {
  const tex::TextureMap map = generated("sine", {}, 128);
  tex::PlaneMapping m = mapping();
  m.plane_to_world = Eigen::Translation3d(0.05, -0.02, 0.1) * Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 1, 0).normalized());
  const tex::TexturedSurface surface(map, m, {}, true);
  ProxyRenderer r(surface, config(true));
  const Eigen::Vector3d tip = m.plane_to_world * Eigen::Vector3d(0.013, 0.007, -0.0015);
  const srv::RenderOutput out = r.render(tip, Eigen::Vector3d::Zero());
  ASSERT_TRUE(out.in_contact);
  ASSERT_GE(out.num_planes, 1);
  for (int i = 0; i < out.num_planes; ++i) {
    const auto& p = out.planes[std::size_t(i)];
    EXPECT_NEAR(p.n_world.norm(), 1.0, 1e-9);
    // The proxy is on or above every plane, and on the active ones.
    EXPECT_GE(p.n_world.dot(out.proxy_world), p.d_m - 1e-9);
    if (out.active_mask & (1u << i)) {
      EXPECT_NEAR(p.n_world.dot(out.proxy_world), p.d_m, 1e-9);
    }
  }
  EXPECT_NEAR((out.proxy_world - tip).norm() * 1000.0, out.force_world.norm(), 1e-6);
}
