// The proxy in DEVICE_STATE (device_state_t.proxy_world, FLAG_PROXY_HELD; docs/messages.md §5.1)
// is the servo's: the servo in lock-step with a scripted pen, every record turned into the message
// exactly as hapticd's publisher does (FaultPipeline), at the full servo rate. The pen hovers,
// presses into a valley of the V-valley relief and slides across the ridges while pressed, then
// lifts: while the tip is below the surface the published proxy is held on it.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/server/fault_pipeline.hpp"

namespace test_published_proxy {

using namespace thx;
using D = thx_msgs::device_state_t;

namespace {

constexpr std::int64_t kPressFrom = 300, kSlideFrom = 400, kLiftAt = 900, kTicks = 1000;

void pressAndSlide(std::int64_t tick, dev::DeviceState& s) {
  test::hover(tick, s);
  if (tick < kPressFrom || tick >= kLiftAt) return;
  // 1 mm below the valley floor's level at 0.1 m/s, then 5 mm across the ridges at 10 mm/s.
  const double z = std::max(0.002 - 1e-4 * double(tick - kPressFrom), -test::kRigValleyDepth - 0.001);
  const double x = test::kRigFloorX + (tick >= kSlideFrom ? 1e-5 * double(tick - kSlideFrom) : 0.0);
  s.p_world = Eigen::Vector3d(x, 0.0, z);
}

struct PublishedProxy : ::testing::Test {
  static void SetUpTestSuite() {
    p = new test::FaultPipeline(pressAndSlide, 1000.0);
    p->run(int(kTicks));
  }
  static void TearDownTestSuite() { delete p; }
  static test::FaultPipeline* p;
};
test::FaultPipeline* PublishedProxy::p = nullptr;

TEST_F(PublishedProxy, EveryMessageCarriesTheServosProxy) {
  ASSERT_EQ(p->sink.state_msgs.size(), p->ticks.size());
  std::size_t held = 0;
  for (std::size_t k = 0; k < p->ticks.size(); ++k) {
    const srv::TickRecord& r = p->ticks[k];
    const D& m = p->sink.state_msgs[k];
    ASSERT_EQ(m.tick, r.tick);
    EXPECT_EQ(bool(m.flags & D::FLAG_PROXY_HELD), r.proxy_held) << "tick " << r.tick;
    for (int i = 0; i < 3; ++i) {
      // Held: the renderer's proxy, bit for bit; free: the tip itself.
      EXPECT_EQ(m.proxy_world[i], r.proxy_held ? r.proxy_world[i] : r.p_world[i]) << "tick " << r.tick << " axis " << i;
    }
    held += r.proxy_held ? 1 : 0;
  }
  EXPECT_GT(held, 500u);  // the press and the slide (scripted: ticks 320..899)
}

TEST_F(PublishedProxy, HeldOnTheSurfaceWhileTheTipIsBelowIt) {
  const tex::TexturedSurface& surface = p->rig.renderer().surface();
  // The map's bilinear depth rounds the valley's floor and ridges off within a texel of the crease
  // (0.35 mm at the floor), where the renderer's planes do not: "below" and "on" are judged with
  // that margin, and "on" only on the planar faces, two texels or more from a crease.
  constexpr double kTexel = 0.1 / 256, kPeriod = 0.004, kCreaseMargin = 0.0004;
  const auto onAFace = [&](double x) {
    const double from_floor = std::abs(std::remainder(x - test::kRigFloorX, kPeriod));  // 0 .. period/2
    return from_floor > 2 * kTexel && from_floor < kPeriod / 2 - 2 * kTexel;
  };
  std::size_t below = 0, on_face = 0;
  for (const D& m : p->sink.state_msgs) {
    const Eigen::Vector3d tip = surface.toLocal(Eigen::Vector3d(m.p_world[0], m.p_world[1], m.p_world[2]));
    const Eigen::Vector3d proxy = surface.toLocal(Eigen::Vector3d(m.proxy_world[0], m.proxy_world[1], m.proxy_world[2]));
    const double tip_depth = surface.at(tip.x(), tip.y()).height_m - tip.z();
    if (!(tip_depth > kCreaseMargin)) continue;
    ++below;
    ASSERT_TRUE(m.flags & D::FLAG_PROXY_HELD) << "tick " << m.tick;
    EXPECT_TRUE(m.flags & D::FLAG_IN_CONTACT) << "tick " << m.tick;
    // Above the tip and on the surface (a god-object: it may stay behind a ridge the tip passed
    // under, so it is not the closest surface point).
    EXPECT_GT(proxy.z(), tip.z()) << "tick " << m.tick;
    if (!onAFace(proxy.x())) continue;
    ++on_face;
    EXPECT_NEAR(proxy.z(), surface.at(proxy.x(), proxy.y()).height_m, 1e-6) << "tick " << m.tick;
  }
  EXPECT_GT(below, 400u);
  EXPECT_GE(on_face, 10u);  // 11: the proxy climbs a face, then waits at the ridge
}

TEST_F(PublishedProxy, FreeAboveTheSurface) {
  for (const D& m : p->sink.state_msgs) {
    if (m.tick >= kPressFrom + 10 && m.tick < kLiftAt) continue;  // the press, the slide (and the first touch)
    EXPECT_FALSE(m.flags & D::FLAG_PROXY_HELD) << "tick " << m.tick;
    for (int i = 0; i < 3; ++i) EXPECT_EQ(m.proxy_world[i], m.p_world[i]) << "tick " << m.tick;
  }
}

}  // namespace

}  // namespace test_published_proxy
