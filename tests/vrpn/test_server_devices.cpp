// hapticd's VRPN server serving several devices (issue 30): Phantom0 and Phantom1, each a held pen
// behind its own servo, on one server. A client reads and commands each by its name, over one
// connection or one per name, and a name's effects reach its own pen only.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "tests/vrpn/served_rig.hpp"

namespace test_server_devices {

using namespace thx;
using namespace thx::vrpn;
using namespace thx::vrpn::test;
using namespace std::chrono_literals;

namespace {

// Two served pens and one server offering them as Phantom0 and Phantom1.
struct TwoPens {
  TwoPens() {
    srv::VrpnServerOptions options;
    options.port = 0;
    options.log = false;
    pens[0].limit(options);
    server = std::make_unique<srv::VrpnServer>(
        std::vector<srv::VrpnServedDevice>{{"Phantom0", pens[0].snapshots, &pens[0].effects},
                                           {"Phantom1", pens[1].snapshots, &pens[1].effects}},
        options);
    server->start();
    for (ServedPen& p : pens) p.startTicking();
  }
  ~TwoPens() {
    for (ServedPen& p : pens) p.stopTicking();
    server->stop();
  }
  std::string tcpAddress(int i) const {
    return "Phantom" + std::to_string(i) + "@tcp://127.0.0.1:" + std::to_string(server->port());
  }

  ServedPen pens[2];
  std::unique_ptr<srv::VrpnServer> server;
};

}  // namespace

TEST(VrpnServerDevices, EachNameReportsItsOwnPen) {
  TwoPens rig;
  rig.pens[0].pen.hold(Eigen::Vector3d(0.01, 0.0, 0.05));
  rig.pens[1].pen.hold(Eigen::Vector3d(-0.02, 0.03, 0.04));
  VrpnClientDevice first(rig.tcpAddress(0), dev::phantomDesktopSpec(), fastClient());
  VrpnClientDevice second(rig.tcpAddress(1), dev::phantomDesktopSpec(), fastClient());
  first.open();
  second.open();
  ASSERT_TRUE(eventually([&] {
    const dev::DeviceState a = first.read(), b = second.read();
    return a.valid && b.valid && a.p_world.x() == 0.01 && b.p_world.x() == -0.02;
  })) << first.status().last_error << " / " << second.status().last_error;
  EXPECT_NEAR(second.read().p_world.y(), 0.03, 1e-12);
  EXPECT_NEAR(first.read().p_world.y(), 0.0, 1e-12);
  first.close();
  second.close();
}

TEST(VrpnServerDevices, OneConnectionCarriesBothNamesAndAPingIsAnsweredByTheNamePinged) {
  TwoPens rig;
  rig.pens[0].pen.hold(Eigen::Vector3d(0.01, 0.0, 0.05));
  rig.pens[1].pen.hold(Eigen::Vector3d(-0.02, 0.03, 0.04));
  RawClient both(rig.server->port(), {"Phantom0", "Phantom1"});
  ASSERT_TRUE(both.waitConnected());
  ASSERT_TRUE(eventually([&] {
    both.pumpFor(2ms);
    return both.last_pos_of["Phantom0"].pos[0] == 0.01 && both.last_pos_of["Phantom1"].pos[0] == -0.02;
  }));
  EXPECT_EQ(both.last_pos_of["Phantom1"].pos[1], 0.03);
  const int pongs0 = both.counts_of["Phantom0"]["vrpn_Base pong_message"];
  both.sendAs("Phantom1", Ping{});
  ASSERT_TRUE(eventually([&] {
    both.pumpFor(2ms);
    return both.counts_of["Phantom1"]["vrpn_Base pong_message"] >= 1;
  }));
  EXPECT_EQ(both.counts_of["Phantom0"]["vrpn_Base pong_message"], pongs0);

  // A client that names only Phantom0 is sent only Phantom0's reports (the others are skipped).
  RawClient one(rig.server->port(), {"Phantom0"});
  ASSERT_TRUE(one.waitConnected());
  ASSERT_TRUE(eventually([&] {
    one.pumpFor(2ms);
    return one.pos_quats > 20;
  }));
  EXPECT_EQ(one.last_pos_of.count("Phantom1"), 0u);
}

TEST(VrpnServerDevices, APlaneCommandedToOneNameIsFeltByItsPenOnly) {
  TwoPens rig;
  const Eigen::Vector3d p0(0.0, 0.0, 0.05), p1(0.02, 0.0, 0.05);
  rig.pens[0].pen.hold(p0);
  rig.pens[1].pen.hold(p1);
  VrpnClientDevice second(rig.tcpAddress(1), dev::phantomDesktopSpec(), fastClient());
  second.open();
  ASSERT_TRUE(eventually([&] { return second.status().connected; })) << second.status().last_error;
  second.write(planeCommandAbove(p1));
  EXPECT_TRUE(eventually([&] { return std::abs(rig.pens[1].pen.force().z() - 0.1) < 1e-3; }))
      << "Phantom1 felt " << rig.pens[1].pen.force().transpose();
  // Phantom0 has ticked through all of that with no effect commanded.
  const std::int64_t t = rig.pens[0].ticks.load();
  ASSERT_TRUE(eventually([&] { return rig.pens[0].ticks.load() > t + 50; }));
  EXPECT_EQ(rig.pens[0].pen.force().norm(), 0.0);
  // The last client gone: Phantom1's effects reset (its client's close has sent a stop surface
  // already, so the force may be gone before the server sees the connection end), Phantom0 had
  // none to reset.
  second.close();
  EXPECT_TRUE(eventually([&] { return rig.server->status().effect_resets >= 1u; }));
  EXPECT_TRUE(eventually([&] { return rig.pens[1].pen.force().norm() < 1e-9; }));
  EXPECT_EQ(rig.server->status().effect_resets, 1u);
}

TEST(VrpnServerDevices, NamesMustBeDistinctAndAtMostSixteen) {
  ServedPen pen;
  const auto refused = [&](std::vector<srv::VrpnServedDevice> devices, const std::string& part) {
    try {
      srv::VrpnServer server(std::move(devices), srv::VrpnServerOptions{});
      ADD_FAILURE() << "accepted; expected: " << part;
    } catch (const thx::Error& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  refused({{"Phantom0", pen.snapshots, nullptr}, {"Phantom0", pen.snapshots, nullptr}}, "two devices named 'Phantom0'");
  refused({}, "serves 1 to 16 devices, asked for 0");
  refused(std::vector<srv::VrpnServedDevice>(17, {"x", pen.snapshots, nullptr}), "asked for 17");
  refused({{"", pen.snapshots, nullptr}}, "device 0 has no name");
  refused({{"Phantom0", nullptr, nullptr}}, "'Phantom0' has no snapshot slot");
}

}  // namespace test_server_devices
