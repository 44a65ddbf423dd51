// `physics-client --replay-log SESSION --record OUT` (the program, as a user runs it): the physics
// streams of a replayed hapticd session go into one log with the session's own events, on the
// session's clock, and two runs write the same bytes.
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "clients/physics_client/pen_path.hpp"
#include "clients/physics_client/physics_scene.hpp"
#include "scenes/scene_loader.hpp"
#include "thx_msgs/protocol.hpp"

namespace test_session_record {

namespace fs = std::filesystem;

namespace {

using namespace thx::physclient;

const std::string kScene = std::string(THX_SOURCE_DIR) + "/scenes/pen_pushes_ball.yaml";
constexpr std::int64_t kUtime0 = 5'000'000;                 // a lock-step session: tick x 1 ms, from tick 5000
constexpr std::int64_t kUnixOffset = 1'700'000'000'000'000;  // hapticd's log timestamps are wall-clock µs

struct Event {
  std::int64_t timestamp;
  std::string channel;
  std::vector<std::uint8_t> data;
};

std::vector<Event> readLog(const std::string& path) {
  std::vector<Event> out;
  lcm::LogFile log(path, "r");
  EXPECT_TRUE(log.good()) << path;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    const auto* b = static_cast<const std::uint8_t*>(e->data);
    out.push_back({e->timestamp, e->channel, std::vector<std::uint8_t>(b, b + e->datalen)});
  }
  return out;
}

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class SessionRecord : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("thx_session_record_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    writeSession(path("session.lcm"));
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // A hapticd session as `hapticd --record` writes it (a device state and a contact per tick), its
  // pen following the scene's hand script over the ball.
  void writeSession(const std::string& file) {
    PhysicsScene sim(thx::scene::loadScene(kScene));
    const std::vector<PenSample> pen = penPathFromScript(sim, 1e-3);
    lcm::LogFile log(file, "w");
    ASSERT_TRUE(log.good());
    std::vector<std::uint8_t> buf;
    auto put = [&](const char* channel, std::int64_t utime, const auto& m) {
      buf.resize(std::size_t(m.getEncodedSize()));
      m.encode(buf.data(), 0, int(buf.size()));
      lcm::LogEvent e{};
      e.timestamp = utime + kUnixOffset;
      e.channel = channel;
      e.datalen = std::int32_t(buf.size());
      e.data = buf.data();
      ASSERT_EQ(log.writeEvent(&e), 0);
    };
    for (std::size_t k = 0; k < pen.size(); ++k) {
      thx_msgs::device_state_t d{};
      d.tick = 5000 + std::int64_t(k);
      d.utime = kUtime0 + std::int64_t(k) * 1000;
      for (int a = 0; a < 3; ++a) d.p_world[a] = pen[k].p_world[a];
      d.q_world[0] = 1.0;
      put("THX_DEVICE_STATE", d.utime, d);
      thx_msgs::contact_t c{};
      c.tick = d.tick;
      c.utime = d.utime;
      put("THX_CONTACT", c.utime, c);
    }
    session_ticks_ = pen.size();
  }

  int record(const std::string& out) {
    const std::string cmd = std::string(THX_PHYSICS_CLIENT) + " --scene " + kScene + " --replay-log " +
                            path("session.lcm") + " --record " + out + " --no-lcm --quiet > /dev/null";
    return std::system(cmd.c_str());
  }

  fs::path dir_;
  std::size_t session_ticks_ = 0;
};

TEST_F(SessionRecord, ReplayedTwiceGivesByteIdenticalPhysicsStreamsOnTheSessionClock) {
  ASSERT_EQ(record(path("a.lcm")), 0);
  ASSERT_EQ(record(path("b.lcm")), 0);
  const std::string a = fileBytes(path("a.lcm"));
  ASSERT_FALSE(a.empty());
  EXPECT_TRUE(a == fileBytes(path("b.lcm"))) << "two replays of one session differ";

  // The session's events are all there, unchanged and in order; the physics events between them.
  const std::vector<Event> session = readLog(path("session.lcm"));
  const std::vector<Event> combined = readLog(path("a.lcm"));
  std::size_t s = 0;
  std::map<std::string, int> physics;
  std::int64_t last_timestamp = 0;
  int texels = 0;
  for (const Event& e : combined) {
    EXPECT_GE(e.timestamp, last_timestamp) << e.channel;
    last_timestamp = e.timestamp;
    if (e.channel.rfind("THX_PHYSICS_", 0) != 0) {
      ASSERT_LT(s, session.size());
      EXPECT_EQ(e.channel, session[s].channel);
      EXPECT_EQ(e.timestamp, session[s].timestamp);
      EXPECT_TRUE(e.data == session[s].data);
      ++s;
      continue;
    }
    ++physics[e.channel];
    // On the session's clock: utime = the log timestamp less the session's own offset.
    std::int64_t utime = 0;
    if (e.channel == thx_msgs::kChannelPhysicsPoses) {
      thx_msgs::physics_poses_t m;
      ASSERT_GT(thx_msgs::try_decode(e.data.data(), e.data.size(), m), 0);
      utime = m.utime;
      EXPECT_EQ(m.utime, kUtime0 + std::llround(m.sim_time * 1e6));
    } else if (e.channel == thx_msgs::kChannelPhysicsContacts) {
      thx_msgs::physics_contacts_t m;
      ASSERT_GT(thx_msgs::try_decode(e.data.data(), e.data.size(), m), 0);
      utime = m.utime;
      texels += m.num_path;
    } else {
      thx_msgs::physics_impact_t m;
      ASSERT_GT(thx_msgs::try_decode(e.data.data(), e.data.size(), m), 0);
      utime = m.utime;
    }
    EXPECT_EQ(utime, e.timestamp - kUnixOffset) << e.channel;
  }
  EXPECT_EQ(s, session.size());
  EXPECT_EQ(session.size(), 2 * session_ticks_);
  EXPECT_GT(physics[thx_msgs::kChannelPhysicsPoses], 100);
  EXPECT_GT(physics[thx_msgs::kChannelPhysicsContacts], 100);
  EXPECT_GT(physics[thx_msgs::kChannelPhysicsImpact], 0);  // the pen hits the ball
  EXPECT_GT(texels, 50);

  // Recording a combined log again replaces its physics events instead of doubling them.
  ASSERT_EQ(std::system((std::string(THX_PHYSICS_CLIENT) + " --scene " + kScene + " --replay-log " + path("a.lcm") +
                         " --record " + path("c.lcm") + " --no-lcm --quiet > /dev/null")
                            .c_str()),
            0);
  EXPECT_TRUE(a == fileBytes(path("c.lcm")));
}

TEST_F(SessionRecord, RecordNeedsAnOfflinePenAndAWritableFile) {
  const std::string bin = THX_PHYSICS_CLIENT;
  EXPECT_NE(std::system((bin + " --scene " + kScene + " --record " + path("x.lcm") + " 2> " + path("err1")).c_str()), 0);
  EXPECT_NE(fileBytes(path("err1")).find("--record needs an offline pen"), std::string::npos) << fileBytes(path("err1"));
  EXPECT_NE(std::system((bin + " --scene " + kScene + " --replay-log " + path("session.lcm") +
                         " --record /nonexistent/dir/x.lcm --no-lcm --quiet > /dev/null 2> " + path("err2"))
                            .c_str()),
            0);
  EXPECT_NE(fileBytes(path("err2")).find("--record /nonexistent/dir/x.lcm: cannot create"), std::string::npos)
      << fileBytes(path("err2"));
}

}  // namespace

}  // namespace test_session_record
