// hapticd --vrpn-listen as a user runs it: a separate process serving its simulated PHANToM, a
// VRPN client in this process (thx_vrpn), and the command-line errors.
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>
#include <thread>

#include "device/vrpn/base_messages.hpp"
#include "device/vrpn/force_messages.hpp"
#include "device/vrpn/tcp_connection.hpp"
#include "device/vrpn/tracker_messages.hpp"
#include "device/vrpn/vrpn_client_device.hpp"
#include "device/device_specs.hpp"
#include "tests/support/hapticd_harness.hpp"
#include "tests/support/vrpn_reports.hpp"

namespace test_hapticd_vrpn_cli {

namespace fs = std::filesystem;
using namespace thx::vrpn;
using namespace std::chrono_literals;

namespace {

using thx::test::ProcRun;

}  // namespace

// hapticd --vrpn-listen serving a simulated PHANToM until the test stops it (serveVrpn, then
// stopChild) once it has what it came for: a fixed --duration raced the test's own connect, which
// a busy VM can starve for seconds.
class HapticdVrpn : public thx::test::HapticdProcessTest {
 protected:
  // Bricks under one simulated pen stroking them slowly for a minute (the
  // default scene's script ends after 4.7 s): the pen moves whenever the test connects.
  std::string strokingScene() {
    std::ofstream(path("stroking.yaml")) << "version: 1\nname: a pen stroking for a minute\nsurface:\n"
                                            "  size: [0.2, 0.2]\n"
                                            "  texture: {generator: bricks, size: 64, params: {extent: 0.2}}\n"
                                            "devices:\n  - name: pen\n    type: sim\n    script:\n"
                                            "      - stroke: {from: [-0.06, -0.03], to: [0.06, 0.03], speed: 0.002, "
                                            "force: 1.0}\n";
    return path("stroking.yaml");
  }
};

TEST_F(HapticdVrpn, BadListenAddressIsAUsageError) {
  for (const char* bad : {"x", "127.0.0.1:", "localhost:3883", "70000", "1.2.3:99"}) {
    const ProcRun r = run(std::string("--scene scenes/default.yaml --no-lcm --vrpn-listen '") + bad + "'");
    EXPECT_EQ(r.status, 2) << bad;
    EXPECT_NE(r.err.find("--vrpn-listen"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(bad), std::string::npos) << r.err;
  }
  const ProcRun r = run("--scene scenes/default.yaml --no-lcm --vrpn-listen 3883 --vrpn-name 'a@b'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--vrpn-name"), std::string::npos) << r.err;
}

TEST_F(HapticdVrpn, APortInUseIsAClearErrorNotACrash) {
  Result<UniqueFd> taken = listenTcp("127.0.0.1", 0);
  ASSERT_TRUE(taken);
  const std::string port = std::to_string(localPort(taken->get()));
  const ProcRun r = run("--scene scenes/default.yaml --no-lcm --no-mlock --lockstep --vrpn-listen " + port);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("--vrpn-listen 127.0.0.1:" + port), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cannot listen"), std::string::npos) << r.err;
}

TEST_F(HapticdVrpn, ServesItsSimulatedPhantomToAVrpnClient) {
  const std::uint16_t port = sparePort();
  const pid_t served = serveVrpn(strokingScene(), port);
  ASSERT_GT(served, 0);
  // Reads reports until they follow the moving pen, however late the client connects.
  const thx::test::VrpnReports got = thx::test::readVrpnReportsUntil(
      port, {"Phantom0"},
      [](const thx::test::VrpnReports& r) {
        const thx::test::SenderReports& pen = r.by_name.at("Phantom0");
        return pen.reports > 0 && pen.x_max > pen.x_min;
      },
      60s);
  const int status = stopChild(served);
  // How many reports arrive depends on the scheduler; that they arrive, decode and follow the
  // moving pen does not.
  const thx::test::SenderReports& pen = got.by_name.at("Phantom0");
  EXPECT_TRUE(got.connected);
  EXPECT_GT(pen.reports, 0);
  EXPECT_EQ(pen.undecodable, 0);
  EXPECT_GT(pen.x_max - pen.x_min, 0.0) << "the scripted stroke moves the pen";
  EXPECT_EQ(status, 0) << servedLog();
  EXPECT_NE(servedLog().find("1 clients served"), std::string::npos) << servedLog();
}

// Our client device against hapticd's server over the UDP request form, the simulated PHANToM
// behind it: the client reads the moving pen and its plane commands reach the server.
TEST_F(HapticdVrpn, OurClientDeviceUsesTheServedPhantomOverTheUdpForm) {
  const std::uint16_t port = sparePort();
  const pid_t served = serveVrpn(strokingScene(), port);
  ASSERT_GT(served, 0);
  VrpnClientOptions o;
  o.reconnect_interval = 100ms;
  o.staleness = 200ms;
  o.command_timeout = 0ns;
  VrpnClientDevice client("Phantom0@127.0.0.1:" + std::to_string(port), thx::dev::phantomDesktopSpec(), o);
  client.open();
  int valid = 0;
  double z_min = 1e9, z_max = -1e9;
  thx::dev::DeviceCommand cmd;
  cmd.forces_enabled = true;
  cmd.num_planes = 1;
  cmd.planes[0].k_n_per_m = 100.0;
  // Until the client has read the moving pen and sent planes, then 2 s more of planes, so that the
  // server has handled some before it is stopped.
  const auto give_up = std::chrono::steady_clock::now() + 60s;
  std::optional<std::chrono::steady_clock::time_point> enough_at;
  for (auto now = std::chrono::steady_clock::now(); now < give_up && !(enough_at && now > *enough_at + 2s);
       now = std::chrono::steady_clock::now()) {
    if (!enough_at && valid > 0 && z_max > z_min && client.status().planes_sent > 0) enough_at = now;
    const thx::dev::DeviceState s = client.read();  // paced at 1 ms
    if (!s.valid) continue;
    ++valid;
    z_min = std::min(z_min, s.p_world.z());
    z_max = std::max(z_max, s.p_world.z());
    cmd.planes[0].d_m = -0.01 + 1e-6 * (valid % 100);  // a plane that changes, far below the pen
    client.write(cmd);
  }
  const int status = stopChild(served);
  const VrpnClientStatus st = client.status();
  client.close();
  const std::string log = servedLog();
  EXPECT_GT(valid, 0) << st.last_error;
  EXPECT_GT(z_max - z_min, 0.0) << "the scripted hand strokes";
  EXPECT_GT(st.planes_sent, 0u);
  EXPECT_EQ(status, 0) << log;
  EXPECT_NE(log.find("1 clients served"), std::string::npos) << log;
  // "hapticd: vrpn: 1 clients served, 0 dropped, 0 refused, N force commands (0 refused)"
  std::smatch m;
  ASSERT_TRUE(std::regex_search(log, m, std::regex("([0-9]+) force commands \\(([0-9]+) refused\\)"))) << log;
  EXPECT_GE(std::stoi(m[1]), 1);
  EXPECT_EQ(std::stoi(m[2]), 0);
}

// --vrpn-plane2: without it hapticd ignores Plane2 like a stock HDAPI PHANToM (docs/vrpn.md §9; the
// sample clients send placeholder values with every report); with it Plane2 is a force command.
TEST_F(HapticdVrpn, Plane2IsIgnoredUnlessVrpnPlane2IsGiven) {
  const ProcRun help = run("--help");
  EXPECT_NE(help.out.find("--vrpn-plane2"), std::string::npos) << help.out;
  for (const bool flag : {false, true}) {
    SCOPED_TRACE(flag ? "--vrpn-plane2" : "default");
    const std::uint16_t port = sparePort(flag ? 1 : 0);
    const pid_t served = serveVrpn("scenes/default.yaml", port,
                                   flag ? std::vector<std::string>{"--device", "sim", "--vrpn-plane2"}
                                        : std::vector<std::string>{"--device", "sim"});
    ASSERT_GT(served, 0);
    // Connect (retrying while hapticd starts), send 3 placeholder Plane2s and then a Ping: the
    // server handles a link's messages in order, so its Pong says the Plane2s have been handled
    // (counted or applied), and only then is it stopped.
    std::unique_ptr<TcpConnection> conn;
    bool sent = false, ponged = false;
    const auto until = std::chrono::steady_clock::now() + 60s;
    while (std::chrono::steady_clock::now() < until && !ponged) {
      if (!conn || !conn->open()) {
        ASSERT_FALSE(sent) << "hapticd closed the link before its Pong";
        Result<UniqueFd> fd = connectTcp("127.0.0.1", port);
        if (!fd) {
          std::this_thread::sleep_for(20ms);
          continue;
        }
        conn = std::make_unique<TcpConnection>(std::move(fd).value());
        conn->endpoint().addSender("Phantom0");
        conn->endpoint().addType(Pong::kTypeName);
      }
      pollfd p{conn->fd(), short(POLLIN | (conn->wantsWrite() ? POLLOUT : 0)), 0};
      ::poll(&p, 1, 5);
      conn->pump();
      while (std::optional<Event> ev = conn->endpoint().poll()) {
        if (std::holds_alternative<Connected>(*ev)) {
          const std::int32_t sender = conn->endpoint().senderId("Phantom0");
          for (int i = 0; i < 3; ++i)
            conn->endpoint().sendMessage(sender, ForcePlane2{0.0001f, 0.0001f, 0.0001f, 0.0001f, 0.0001f, 0.0001f});
          conn->endpoint().sendMessage(sender, Ping{});
          sent = true;
        } else if (const auto* m = std::get_if<UserMessage>(&*ev); m && m->type_name == Pong::kTypeName) {
          ponged = true;
        }
      }
    }
    const int status = stopChild(served);
    if (conn) conn->close(Error{ErrorCode::kPeerClosed, "test done"});
    const std::string log = servedLog();
    ASSERT_TRUE(ponged) << log;
    EXPECT_EQ(status, 0) << log;
    // "..., N force commands (0 refused), M reports skipped for slow readers, K Plane2 ignored"
    std::smatch m;
    ASSERT_TRUE(std::regex_search(
        log, m,
        std::regex("([0-9]+) force commands \\([0-9]+ refused\\), [0-9]+ reports skipped for slow readers, "
                   "([0-9]+) Plane2 ignored")))
        << log;
    EXPECT_EQ(std::stoi(m[1]), flag ? 3 : 0);
    EXPECT_EQ(std::stoi(m[2]), flag ? 0 : 3);
  }
}

}  // namespace test_hapticd_vrpn_cli
