// Plane-proxy rendering on textured planes: spring law, relief contact, crease handling in a
// steep V-valley, the recovery rule, world-frame planes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <numbers>

#include "server/proxy_renderer.hpp"
#include "tests/support/generated_texture.hpp"
#include "tests/support/same_render_output.hpp"
#include "tests/support/sanitized_build.hpp"

namespace test_proxy_renderer {

using namespace thx;
using srv::ProxyRenderer;
using srv::RendererConfig;

namespace {

constexpr double kExtent = 0.2;

tex::TextureMap generated(const std::string& kind, std::map<std::string, double> params, int size = 512) {
  return test::generatedTexture(kind, std::move(params), size, kExtent);
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

// ---- Ridges (issue 12): the convex creases of a V-valley ----------------------------------------

namespace {

// The exact V-valley of generated("vvalley", 60 deg, period 4 mm) at `size` texels, in the plane
// frame: z = h(X) - h_top with X = x + extent / 2, h_top the highest texel centre (the generator's
// depth = h_top - h), and the closest point of that continuous surface to a probe below it.
struct ExactVValley {
  double period = 0.004, slope = std::tan(kAlpha), h_top = 0.0;
  explicit ExactVValley(int size) {
    h_top = -1e9;
    for (int i = 0; i < size; ++i) h_top = std::max(h_top, h((i + 0.5) * kExtent / size));
  }
  double h(double X) const {
    const double f = X / period - std::floor(X / period);
    return -slope * period * (f < 0.5 ? f : 1.0 - f);
  }
  double z(double x) const { return h(x + kExtent / 2) - h_top; }
  // Closest point in the (x, z) cross-section: the nearest of the wall segments around x.
  Eigen::Vector2d closest(double x, double pz) const {
    const double X = x + kExtent / 2, floor_z = -slope * period / 2 - h_top;
    Eigen::Vector2d best(x, pz);
    double best_d2 = 1e300;
    for (long long m = (long long)std::floor(X / period) - 1; m <= (long long)std::floor(X / period) + 1; ++m) {
      const double xr = double(m) * period;
      const Eigen::Vector2d ends[3] = {{xr, -h_top}, {xr + period / 2, floor_z}, {xr + period, -h_top}};
      for (int s = 0; s < 2; ++s) {
        const Eigen::Vector2d a = ends[s], d = ends[s + 1] - ends[s];
        const double t = std::clamp((Eigen::Vector2d(X, pz) - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
        const Eigen::Vector2d q = a + t * d;
        const double d2 = (q - Eigen::Vector2d(X, pz)).squaredNorm();
        if (d2 < best_d2) {
          best_d2 = d2;
          best = {q.x() - kExtent / 2, q.y()};
        }
      }
    }
    return best;
  }
};

// bench_force_error's press: from 0.5 mm above the base plane down at 20 um per tick to the probe,
// then 15 ticks still; returns the last output.
srv::RenderOutput press(ProxyRenderer& r, const Eigen::Vector3d& p) {
  r.reset();
  const Eigen::Vector3d v_down(0, 0, -0.02);
  for (double z = 0.0005; z > p.z(); z -= 2e-5) r.render({p.x(), p.y(), z}, v_down);
  srv::RenderOutput out;
  for (int k = 0; k < 15; ++k) out = r.render(p, Eigen::Vector3d::Zero());
  return out;
}

}  // namespace

// The issue-12 goal, pinned by a computed (not timed) sweep: 60 deg V-valleys at 512² (0.39 mm
// texels, 10.24 per period) pressed at 400 evenly spaced points across two periods and four
// depths, as bench_force_error presses them. With sided ridges the RMS force error stays under
// 5 % of the RMS exact force (here 0.0012 %; bench_force_error: 0.0013 %, the 16-bit depth code);
// issue 3's renderer, which blends the two walls' normals across a ridge, is at 24.8 % here
// (27.6 % in the benchmark), all of it next to the ridges: a press beside a ridge slid over it
// onto the far wall, and 8 light presses touched nothing.
TEST(ProxyRenderer, VValleyForceErrorAt512IsUnderFivePercentWithSidedRidges) {
  const int size = 512;
  const tex::TextureMap map = generated("vvalley", {{"angle_deg", 60.0}, {"period", 0.004}}, size);
  const tex::TexturedSurface surface(map, mapping(), {}, true);
  const ExactVValley exact(size);
  auto relativeRms = [&](bool sided, int& no_contact, double& ridge_share) {
    RendererConfig c = config(true, 10);
    c.sided_ridges = sided;
    ProxyRenderer r(surface, c);
    double e2 = 0.0, f2 = 0.0, e2_ridge = 0.0;
    no_contact = 0;
    const int probes = thx::test::kSanitized ? 100 : 400;  // 100: still ~14 in each ridge band
    for (int k = 0; k < probes; ++k) {
      const double x = -0.004 + 0.008 * (k + 0.5) / probes, y = 0.0013 * k;  // y: any, the valley runs along it
      for (double depth : {0.25e-3, 0.5e-3, 1e-3, 2e-3}) {
        const Eigen::Vector3d p(x, y, exact.z(x) - depth);
        const Eigen::Vector2d q = exact.closest(x, p.z());
        const Eigen::Vector3d f_exact = 1000.0 * Eigen::Vector3d(q.x() - x, 0.0, q.y() - p.z());
        const srv::RenderOutput out = press(r, p);
        no_contact += out.in_contact ? 0 : 1;
        const double e = (out.force_world - f_exact).squaredNorm();
        e2 += e;
        f2 += f_exact.squaredNorm();
        const double X = x + kExtent / 2, f = X / 0.004 - std::floor(X / 0.004);
        if (std::min(f, 1.0 - f) * 0.004 < 1.5 * kExtent / size) e2_ridge += e;  // within 1.5 texels of a ridge
      }
    }
    ridge_share = e2 > 0.0 ? e2_ridge / e2 : 0.0;
    return std::sqrt(e2 / f2);
  };
  int no_contact_sided = 0, no_contact_blend = 0;
  double ridge_sided = 0.0, ridge_blend = 0.0;
  const double sided = relativeRms(true, no_contact_sided, ridge_sided);
  const double blend = relativeRms(false, no_contact_blend, ridge_blend);
  EXPECT_LT(sided, 0.05);
  EXPECT_LT(sided, 1e-4);  // the texel planes of a V are its walls: exact but for the 16-bit depth code
  EXPECT_EQ(no_contact_sided, 0);
  EXPECT_GT(blend, 0.15);        // the sweep tells the two apart
  EXPECT_GT(ridge_blend, 0.99);  // and the blended error is all next to the ridges
}

// Next to a ridge the tip takes the plane of its own side, wherever the ridge falls within the
// texel, and a light touch on the ridge is felt: the bilinear depth rounds the ridge down by up to
// slope x half a texel (0.34 mm at 512²), so a press 0.1 mm below the true ridge got no contact.
TEST(ProxyRenderer, ARidgeIsFeltOnTheSideTheTipIsOn) {
  const int size = 512;
  const tex::TextureMap map = generated("vvalley", {{"angle_deg", 60.0}, {"period", 0.004}}, size);
  const tex::TexturedSurface surface(map, mapping(), {}, true);
  const ExactVValley exact(size);
  ProxyRenderer sided(surface, config(true, 10));
  RendererConfig blend_config = config(true, 10);
  blend_config.sided_ridges = false;
  ProxyRenderer blend(surface, blend_config);
  const double ridge_x = 0.0;  // X = extent / 2 = 25 periods: a ridge line
  int blend_wrong_side = 0, blend_no_contact = 0;
  for (double offset : {-0.15e-3, -0.05e-3, -0.01e-3, 0.01e-3, 0.05e-3, 0.15e-3}) {
    const double x = ridge_x + offset;
    for (double depth : {0.1e-3, 1e-3}) {
      const Eigen::Vector3d p(x, 0.0, exact.z(x) - depth);
      const srv::RenderOutput out = press(sided, p);
      ASSERT_TRUE(out.in_contact) << offset << " " << depth;
      // The wall on the tip's side pushes away from the ridge: left of it towards -x.
      EXPECT_GT(out.force_world.x() * offset, 0.0) << offset << " " << depth;
      // Exact but for the 16-bit depth code (a 53 nm step here: 53 uN at 1000 N/m).
      const Eigen::Vector2d q = exact.closest(x, p.z());
      EXPECT_NEAR(out.force_world.x(), 1000.0 * (q.x() - x), 1e-4) << offset << " " << depth;
      EXPECT_NEAR(out.force_world.z(), 1000.0 * (q.y() - p.z()), 1e-4) << offset << " " << depth;
      const srv::RenderOutput old = press(blend, p);
      blend_no_contact += old.in_contact ? 0 : 1;
      blend_wrong_side += old.in_contact && old.force_world.x() * offset < 0.0 ? 1 : 0;
    }
  }
  EXPECT_GT(blend_no_contact + blend_wrong_side, 0);  // what issue 3's renderer did here
}

// Smooth relief keeps its interpolated normal: a sine at 256² (12.8 texels per period) bends by up
// to 9 deg between neighbouring texels, more than the crease angle, but spreads the bend over the
// texels beside it, so no bend is read as a ridge and sided and blended rendering agree to the
// last bit. (At 128², 6.4 texels per period, a convex bend next to a concave one passes for a
// ridge in places: 2 % of bench_force_error's probes, RMS error 10.80 -> 10.77 %.)
TEST(ProxyRenderer, ACoarselySampledSmoothBumpIsNotARidge) {
  const tex::TextureMap map = generated("sine", {}, 256);
  const tex::TexturedSurface surface(map, mapping(), {}, true);
  ProxyRenderer sided(surface, config(true, 10));
  RendererConfig blend_config = config(true, 10);
  blend_config.sided_ridges = false;
  ProxyRenderer blend(surface, blend_config);
  // Around the tops of 25 bumps (x, y = 2.5 mm + 10 mm m: sin kX = sin kY = 1), where the bends
  // are sharpest, 0.5 mm into the surface.
  for (int k = 0; k < 200; ++k) {
    const double x = 0.0025 + 0.01 * (k % 5) + 0.003 * ((k * 7 % 20) / 19.0 - 0.5);
    const double y = 0.0025 + 0.01 * (k / 5 % 5) + 0.003 * ((k * 13 % 20) / 19.0 - 0.5);
    const double z = -double(map.depth(int((x / kExtent + 0.5) * 256), int((0.5 - y / kExtent) * 256))) - 0.0005;
    const srv::RenderOutput a = press(sided, {x, y, z}), b = press(blend, {x, y, z});
    EXPECT_EQ(a.in_contact, b.in_contact) << k;
    EXPECT_EQ(a.force_world, b.force_world) << k;
  }
}

// The servo renders in two halves, the force before it is written and where the contact is after
// (server/servo.cpp): together they say what render() says, to the bit, in every mode, on a plane
// placed off the world's axes, through entering, sliding over a relief's creases, leaving, and a
// non-finite tip; the first half alone already holds the force's fields; and the description is
// in the world's frame (against the same plane at the origin).
TEST(ProxyRenderer, RendersInTwoHalvesWhatRenderDoes) {
  const tex::TextureMap map = generated("vvalley", {{"angle_deg", 60.0}, {"period", 0.004}});
  tex::PlaneMapping placed = mapping();
  placed.plane_to_world.translate(Eigen::Vector3d(0.01, -0.02, 0.03));
  placed.plane_to_world.rotate(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, -2, 0.5).normalized()));
  const tex::TexturedSurface surface(map, placed, {}, true);
  RendererConfig paper = config(false);
  paper.plane_hold_ticks = 4;
  const tex::TexturedSurface at_origin(map, mapping(), {}, true);
  for (const RendererConfig& c : {config(true, 10), config(false, 10), paper}) {
    ProxyRenderer whole(surface, c), halves(surface, c), local(at_origin, c);
    int contact = 0;
    for (int k = 0; k < 1200; ++k) {
      const double x = 1e-5 * k, depth = k % 400 < 300 ? 0.004 : -0.001;  // out of contact 100 ticks in 400
      Eigen::Vector3d local_tip(x, 0.3 * x, -depth);
      const Eigen::Vector3d local_v(0.01, 0.003, -0.002);
      if (k == 650) local_tip.x() = std::numeric_limits<double>::quiet_NaN();
      const Eigen::Vector3d tip = placed.plane_to_world * local_tip;
      const Eigen::Vector3d v = placed.plane_to_world.linear() * local_v;
      const srv::RenderOutput a = whole.render(tip, v);
      srv::RenderOutput b = halves.renderForce(tip, v);
      const std::string where = "hold " + std::to_string(c.plane_hold_ticks) + ", crease " +
                                std::to_string(c.crease_handling) + ", tick " + std::to_string(k);
      test::expectSameForce(a, b, where);
      halves.describeContact(b);
      test::expectSameOutput(a, b, where);
      const srv::RenderOutput l = local.render(local_tip, local_v);
      if (k != 650 && l.in_contact == b.in_contact) test::expectDescribedAt(placed.plane_to_world, l, b, 1e-9, where);
      contact += a.in_contact ? 1 : 0;
    }
    EXPECT_GT(contact, 500);
  }
}

}  // namespace test_proxy_renderer
