// A pen with extent drawn (issue 30): a device whose scene tool is a capsule is drawn as that
// capsule, its ball of the tool's radius at hapticd's tool tip and its shaft along the device's
// orientation, which the frames of a recorded session carry; other devices keep the point pen.
#include <gtest/gtest.h>

#include <cmath>

#include "clients/visual/live_view.hpp"
#include "clients/visual/replay_frames.hpp"
#include "clients/visual/scene_objects.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_surface.hpp"
#include "server/session_log.hpp"
#include "tests/support/temp_dir.hpp"

namespace thx::visual::test_pen_tool_view {
namespace {

const std::string kCapsuleScene = std::string(THX_SOURCE_DIR) + "/scenes/capsule_bricks.yaml";

// The pen lying along +x: the device's +z turned a quarter about y.
Eigen::Quaterniond lyingAlongX() { return Eigen::Quaterniond(Eigen::AngleAxisd(0.5 * M_PI, Eigen::Vector3d::UnitY())); }

}  // namespace

TEST(VisualPenTool, ACapsuleToolIsDrawnAlongTheDevicesAxisFromItsTip) {
  const scene::Scene sc = scene::loadScene(kCapsuleScene);
  const scene::SceneSurface surface = scene::buildSceneSurface(sc);
  PenView pen;
  pen.tip_world = pen.proxy_world = Eigen::Vector3d(0.01, 0.02, 0.005);
  pen.q_world = lyingAlongX();
  const std::vector<ObjectInstance> drawn = pensAt(surface.surface, {pen}, &sc);
  ASSERT_EQ(drawn.size(), 2u);  // ball and shaft
  const double r = sc.device.tool.radius_m, length = sc.device.tool.length_m;
  EXPECT_EQ(drawn[0].shape, UnitShape::Sphere);
  EXPECT_TRUE(drawn[0].model.translation().isApprox(pen.proxy_world, 1e-12));
  EXPECT_NEAR(drawn[0].model.linear().col(0).norm(), r, 1e-12);
  EXPECT_EQ(drawn[1].shape, UnitShape::Cylinder);
  EXPECT_TRUE(drawn[1].model.translation().isApprox(pen.proxy_world + Eigen::Vector3d(0.5 * length, 0, 0), 1e-12));
  // The unit cylinder's axis (its z) becomes the shaft: along +x, the tool's length.
  EXPECT_TRUE(drawn[1].model.linear().col(2).isApprox(Eigen::Vector3d(length, 0, 0), 1e-12));
  EXPECT_NEAR(drawn[1].model.linear().col(0).norm(), r, 1e-12);

  // Held (the device's tip in the bricks, the tool's on them): the ball at the tool's tip in the
  // held colour, the device's tip a small ball with a rod to it.
  PenView held = pen;
  held.tip_world.z() = -0.001;
  held.proxy_held = true;
  const std::vector<ObjectInstance> with_tip = pensAt(surface.surface, {held}, &sc);
  ASSERT_EQ(with_tip.size(), 4u);
  EXPECT_TRUE(with_tip[0].model.translation().isApprox(held.proxy_world, 1e-12));
  EXPECT_NE(with_tip[0].albedo, drawn[0].albedo);
  EXPECT_TRUE(with_tip[2].model.translation().isApprox(held.tip_world, 1e-12));

  // Without the scene (or for a point-pen device) the point pen, upright at the tip, as before.
  const std::vector<ObjectInstance> point = pensAt(surface.surface, {pen});
  ASSERT_EQ(point.size(), 2u);
  EXPECT_LT(point[0].model.linear().col(0).norm(), 0.002);
  EXPECT_TRUE(point[1].model.linear().col(2).normalized().isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
  // At rest, the capsule stands on the surface: its ball's centre one radius above it.
  const std::vector<ObjectInstance> rest = pensAtRest(surface.surface, sc, std::nullopt, Eigen::Vector2d(0.0, 0.01));
  ASSERT_EQ(rest.size(), 2u);
  const Eigen::Vector3d on = tipOnSurface(surface.surface, Eigen::Vector2d(0.0, 0.01));
  EXPECT_NEAR(rest[0].model.translation().z(), on.z() + r, 1e-12);
  EXPECT_TRUE(rest[1].model.linear().col(2).isApprox(Eigen::Vector3d(0, 0, length), 1e-12));
}

TEST(VisualPenTool, RecordedAndLiveStatesCarryTheDevicesOrientation) {
  const test::TempDir dir("visual_pen_tool");
  const std::string log = dir.file("tool.lcm");
  const Eigen::Quaterniond q = lyingAlongX();
  {
    srv::SessionRecorder rec(log, true);
    for (std::int64_t t = 0; t < 200; ++t) {
      srv::TickRecord r;
      r.tick = t;
      r.deadline_ns = t * 1'000'000;
      r.q_world[0] = q.w(), r.q_world[1] = q.x(), r.q_world[2] = q.y(), r.q_world[3] = q.z();
      rec.record(r, 0);
    }
    ASSERT_TRUE(rec.ok()) << rec.error();
  }
  const std::vector<ReplayFrame> frames = replayFrames(log, 1000.0, 10.0);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_TRUE(pensOf(frames[1]).front().q_world.isApprox(q, 1e-12));
  thx_msgs::device_state_t s{};  // all zero: a state without an orientation is drawn upright
  EXPECT_TRUE(penViewOf(s).q_world.isApprox(Eigen::Quaterniond::Identity()));
  s.q_world[0] = 2.0 * q.w(), s.q_world[2] = 2.0 * q.y();  // normalised
  EXPECT_TRUE(penViewOf(s).q_world.isApprox(q, 1e-12));
}

}  // namespace thx::visual::test_pen_tool_view
