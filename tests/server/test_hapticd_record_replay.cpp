// hapticd --record and --device replay:FILE as a user runs them (separate processes, lock-step):
// a recorded session replays with the same contact states, deterministically, and can be
// rendered again with other settings.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <Eigen/Core>
#include <thx_msgs/log_reader.hpp>

#include "server/session_log.hpp"
#include "tests/support/hapticd_harness.hpp"

namespace test_hapticd_record_replay {

namespace fs = std::filesystem;
using thx_msgs::contact_t;

namespace {

// hapticd without LCM or memory locking, flight records in the scratch directory. Exit status;
// stderr in err_.
class HapticdRecordReplay : public thx::test::HapticdProcessTest {
 protected:
  int run(const std::string& args) {
    const thx::test::ProcRun r =
        HapticdProcessTest::run(args + " --no-lcm --no-mlock --flight-dir '" + dir_.string() + "'");
    err_ = r.err;
    return r.status;
  }
  std::string err_;
};

bool sameContact(const contact_t& a, const contact_t& b) {
  if (a.tick != b.tick || a.in_contact != b.in_contact || a.num_planes != b.num_planes ||
      a.texel_i != b.texel_i || a.texel_j != b.texel_j || a.depth != b.depth || a.f_normal != b.f_normal)
    return false;
  for (int k = 0; k < 3; ++k)
    if (a.p_proj_world[k] != b.p_proj_world[k] || a.n_sampled_world[k] != b.n_sampled_world[k]) return false;
  return true;
}

}  // namespace

TEST_F(HapticdRecordReplay, ARecordedSessionReplaysWithTheSameContactStates) {
  ASSERT_EQ(run("--scene scenes/default.yaml --lockstep --record " + path("rec.lcm")), 0) << err_;
  EXPECT_NE(err_.find("recorded"), std::string::npos) << err_;
  ASSERT_EQ(run("--scene scenes/default.yaml --lockstep --device replay:" + path("rec.lcm") + " --record " +
                path("replay.lcm")),
            0)
      << err_;
  EXPECT_NE(err_.find("replaying"), std::string::npos) << err_;

  const std::vector<contact_t> rec = thx::srv::loadSessionContacts(path("rec.lcm"));
  const std::vector<contact_t> rep = thx::srv::loadSessionContacts(path("replay.lcm"));
  ASSERT_GT(rec.size(), 1000u);
  ASSERT_GE(rep.size(), rec.size());  // the replay also ramps out after its last sample
  // The session names its scene: one hello (no switch), before the first tick, on its clock.
  const std::vector<thx_msgs::hello_t> hellos = thx::srv::loadSessionHellos(path("rec.lcm"));
  ASSERT_EQ(hellos.size(), 1u);
  EXPECT_EQ(hellos[0].scene_name, "default");
  EXPECT_EQ(hellos[0].utime, rec.front().utime);
  std::size_t contacts = 0, differing = 0;
  for (std::size_t i = 0; i < rec.size(); ++i) {
    if (rec[i].in_contact) ++contacts;
    if (!sameContact(rec[i], rep[i])) ++differing;
  }
  EXPECT_GT(contacts, 500u) << "the default scene's hand presses and strokes";
  EXPECT_EQ(differing, 0u) << "of " << rec.size() << " ticks";
  // Lock-step recording drops nothing: ticks run 0, 1, 2, ... without a gap.
  for (std::size_t i = 0; i < rec.size(); ++i) ASSERT_EQ(rec[i].tick, std::int64_t(i));
}

TEST_F(HapticdRecordReplay, ReplayIsDeterministicAndOtherSettingsRenderDifferently) {
  ASSERT_EQ(run("--scene scenes/vvalley.yaml --lockstep --record " + path("rec.lcm")), 0) << err_;
  const std::string replay = " --scene scenes/vvalley.yaml --lockstep --device replay:" + path("rec.lcm");
  ASSERT_EQ(run(replay + " --record " + path("a.lcm")), 0) << err_;
  ASSERT_EQ(run(replay + " --record " + path("b.lcm")), 0) << err_;
  ASSERT_EQ(run(replay + " --no-crease --record " + path("single.lcm")), 0) << err_;
  const auto a = thx::srv::loadSessionContacts(path("a.lcm"));
  const auto b = thx::srv::loadSessionContacts(path("b.lcm"));
  const auto single = thx::srv::loadSessionContacts(path("single.lcm"));
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_TRUE(sameContact(a[i], b[i])) << "tick " << a[i].tick;
  // Single-plane rendering of the same pen path: never more than one plane, and a different
  // contact somewhere in the valley.
  ASSERT_EQ(single.size(), a.size());
  std::size_t multi_plane = 0, differing = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_LE(single[i].num_planes, 1) << i;
    if (a[i].num_planes > 1) ++multi_plane;
    if (!sameContact(a[i], single[i])) ++differing;
  }
  EXPECT_GT(multi_plane, 0u) << "crease handling holds two walls at the valley floor";
  EXPECT_GT(differing, 0u);
}

// The proxy as hapticd records and publishes it (device_state_t.proxy_world, FLAG_PROXY_HELD): on
// vvalley's hand path, whenever it is held the tip is inside the proxy planes of that tick's
// contact sample and the proxy lies on one of them, above the tip; otherwise it is the tip.
TEST_F(HapticdRecordReplay, TheRecordedProxyIsHeldOnTheSurfaceWhileTheTipIsBelowIt) {
  ASSERT_EQ(run("--scene scenes/vvalley.yaml --lockstep --record " + path("rec.lcm")), 0) << err_;
  using D = thx_msgs::device_state_t;
  std::vector<D> states;
  thx_msgs::forEachLogMessage<D>(path("rec.lcm"), thx::srv::kSessionDeviceChannel,
                                 [&](const D& d, const thx_msgs::LogPosition&) { states.push_back(d); });
  const std::vector<contact_t> contacts = thx::srv::loadSessionContacts(path("rec.lcm"));
  ASSERT_EQ(states.size(), contacts.size());
  std::size_t held = 0;
  for (std::size_t i = 0; i < states.size(); ++i) {
    const D& d = states[i];
    const contact_t& c = contacts[i];
    ASSERT_EQ(d.tick, c.tick);
    const Eigen::Vector3d tip(d.p_world[0], d.p_world[1], d.p_world[2]);
    const Eigen::Vector3d proxy(d.proxy_world[0], d.proxy_world[1], d.proxy_world[2]);
    if (!(d.flags & D::FLAG_PROXY_HELD)) {
      EXPECT_EQ(proxy, tip) << "tick " << d.tick;
      continue;
    }
    ++held;
    EXPECT_TRUE(d.flags & D::FLAG_IN_CONTACT) << "tick " << d.tick;
    ASSERT_GE(c.num_planes, 1) << "tick " << d.tick;
    EXPECT_GT(c.depth, 0.0) << "tick " << d.tick;  // the tip below the primary plane
    double nearest = 1e9;
    for (int k = 0; k < c.num_planes; ++k) {
      const Eigen::Vector3d n(c.plane_n_world[k][0], c.plane_n_world[k][1], c.plane_n_world[k][2]);
      nearest = std::min(nearest, std::abs(n.dot(proxy) - c.plane_d[k]));
      EXPECT_GE(n.dot(proxy) - c.plane_d[k], -1e-9) << "tick " << d.tick << ": the proxy inside plane " << k;
    }
    EXPECT_LT(nearest, 1e-9) << "tick " << d.tick << ": the proxy on none of its planes";
  }
  EXPECT_GT(held, 500u) << "vvalley's hand presses into the valleys";
}

TEST_F(HapticdRecordReplay, BadReplayAndRecordFilesAreClearErrors) {
  EXPECT_EQ(run("--scene scenes/default.yaml --lockstep --device replay:" + path("missing.lcm")), 1);
  EXPECT_NE(err_.find("missing.lcm: cannot open as an LCM log file"), std::string::npos) << err_;
  std::ofstream(path("text.lcm")) << "hello\n";
  EXPECT_EQ(run("--scene scenes/default.yaml --lockstep --device replay:" + path("text.lcm")), 1);
  EXPECT_NE(err_.find("text.lcm"), std::string::npos) << err_;
  EXPECT_EQ(run("--scene scenes/default.yaml --lockstep --record /nonexistent/dir/x.lcm"), 1);
  EXPECT_NE(err_.find("--record /nonexistent/dir/x.lcm: cannot create"), std::string::npos) << err_;
  EXPECT_EQ(run("--scene scenes/default.yaml --device replay:"), 2);
}

}  // namespace test_hapticd_record_replay
