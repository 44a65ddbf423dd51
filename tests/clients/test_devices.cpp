// The kit's Client on a server with several devices (protocol 6, issue 30; docs/clients.md §3.4):
// it follows one device, and the other devices' messages interleaved on its channels reach none
// of its callbacks or latest values but are counted; every device's newest state is kept by
// index; the other devices' traffic still shows the stream alive; ClientApp refuses a device the
// hello does not name. The fake hapticd of tests/support grants the streams over memq:// with a
// fake clock; the test publishes the devices' messages on the granted channels.
#include <gtest/gtest.h>

#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>
#include <thx_msgs/protocol.hpp>

#include "base/error.hpp"
#include "tests/clients/device_messages.hpp"
#include "tests/support/fake_server.hpp"
#include "thx_client/app.hpp"
#include "thx_client/client.hpp"
#include "thx_client/devices.hpp"
#include "thx_client/stop_signal.hpp"

namespace test_devices {

using namespace thx;
using client::Client;
using thx_msgs::Stream;
using Seen = std::vector<std::pair<int, std::int64_t>>;  // (device, tick or seq) per delivery

namespace {

constexpr std::int64_t kMs = 1'000'000;

// The message of the thx::Error of kind Config that f() throws; else what it threw instead.
std::string configErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const thx::Error& e) {
    return (e.kind() == thx::Error::Kind::Config ? "" : "<not Config> ") + std::string(e.what());
  }
  return "<no thx::Error>";
}

class DeviceClientTest : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(lcm_.good()); }
  std::unique_ptr<Client> makeClient(const std::string& id, int device, bool every_device = false) {
    client::ClientOptions o;
    o.client_id = id;
    o.clock = [this] { return now_; };
    o.device = device;
    o.every_device = every_device;
    return std::make_unique<Client>(lcm_, o);
  }
  void pump(Client& c) {
    for (int k = 0; k < 4; ++k) c.poll(0);
  }
  template <class M>
  void publish(const Client& c, Stream stream, const M& m) {
    lcm_.publish(c.status(stream)->channel, &m);
  }

  lcm::LCM lcm_{"memq://"};
  std::int64_t now_ = 1'000 * kMs;
};

}  // namespace

TEST_F(DeviceClientTest, ADeviceZeroClientGetsNoneOfDeviceOnesMessagesAndCountsThem) {
  test::FakeServer server(lcm_, 11, now_);
  auto c = makeClient("visual", 0);
  EXPECT_EQ(c->device(), 0);
  Seen states, contacts, stats;
  c->onDeviceState([&](const thx_msgs::device_state_t& m, std::int64_t) { states.emplace_back(m.device, m.tick); });
  c->onContact([&](const thx_msgs::contact_t& m, std::int64_t) { contacts.emplace_back(m.device, m.tick); });
  c->onServoStats([&](const thx_msgs::servo_stats_t& m, std::int64_t) { stats.emplace_back(m.device, m.ticks); });
  c->subscribe(Stream::DeviceState, 100.0);
  c->subscribe(Stream::Contact, 100.0);
  c->subscribe(Stream::ServoStats, 1.0);
  pump(*c);
  ASSERT_TRUE(c->allActive());
  for (std::int64_t tick = 10; tick <= 30; tick += 10) {
    for (int device : {0, 1}) {  // interleaved on each channel, as hapticd sends them
      publish(*c, Stream::DeviceState, test::deviceState(device, tick));
      publish(*c, Stream::Contact, test::contactSample(device, tick));
      publish(*c, Stream::ServoStats, test::servoStats(device, tick * 100));
    }
  }
  pump(*c);
  EXPECT_EQ(states, (Seen{{0, 10}, {0, 20}, {0, 30}}));
  EXPECT_EQ(contacts, (Seen{{0, 10}, {0, 20}, {0, 30}}));
  EXPECT_EQ(stats, (Seen{{0, 1000}, {0, 2000}, {0, 3000}}));
  ASSERT_TRUE(c->latestDeviceState());
  EXPECT_EQ(c->latestDeviceState()->device, 0);
  EXPECT_EQ(c->latestDeviceState()->p_world[0], test::penX(0));  // its own pen, never device 1's
  EXPECT_EQ(c->latestContact()->device, 0);
  EXPECT_EQ(c->latestContact()->tick, 30);
  EXPECT_EQ(c->latestServoStats()->device, 0);
  for (Stream s : {Stream::DeviceState, Stream::Contact, Stream::ServoStats}) {
    EXPECT_EQ(c->status(s)->messages, 3u) << thx_msgs::stream_name(s);
    EXPECT_EQ(c->status(s)->other_device, 3u) << thx_msgs::stream_name(s);
  }
  EXPECT_EQ(c->counters().other_device, 9u);
  // Every device's newest state, by index, for a client of several pens.
  ASSERT_TRUE(c->latestDeviceState(1));
  EXPECT_EQ(c->latestDeviceState(1)->device, 1);
  EXPECT_EQ(c->latestDeviceState(1)->tick, 30);
  EXPECT_EQ(c->latestDeviceState(1)->p_world[0], test::penX(1));
  EXPECT_EQ(c->latestDeviceState(0)->p_world[0], test::penX(0));
  EXPECT_FALSE(c->latestDeviceState(2));   // never seen
  EXPECT_FALSE(c->latestDeviceState(-1));  // outside the table
  EXPECT_FALSE(c->latestDeviceState(client::kMaxDevices));
}

TEST_F(DeviceClientTest, AClientFollowingDeviceOneGetsOnlyDeviceOnes) {
  test::FakeServer server(lcm_, 11, now_);
  auto c = makeClient("audio", 1);
  Seen batches, states;
  c->onContactBatch([&](const thx_msgs::contact_batch_t& b, std::int64_t) {
    batches.emplace_back(b.device, b.seq);
    for (const auto& s : b.samples) EXPECT_EQ(s.device, 1);
  });
  c->onDeviceState([&](const thx_msgs::device_state_t& m, std::int64_t) { states.emplace_back(m.device, m.tick); });
  c->subscribe(Stream::Contact, 100.0, /*batch=*/true);
  c->subscribe(Stream::DeviceState, 100.0);
  pump(*c);
  ASSERT_TRUE(c->allActive());
  for (std::int64_t seq = 1; seq <= 3; ++seq) {
    for (int device : {1, 0}) {  // each device's batch seq counts on its own: 1, 2, 3 for both
      publish(*c, Stream::Contact, test::contactBatch(device, seq, (seq - 1) * 10));
      publish(*c, Stream::DeviceState, test::deviceState(device, seq * 10 - 1));
    }
  }
  pump(*c);
  EXPECT_EQ(batches, (Seen{{1, 1}, {1, 2}, {1, 3}}));
  EXPECT_EQ(states, (Seen{{1, 9}, {1, 19}, {1, 29}}));
  EXPECT_EQ(c->latestContactBatch()->device, 1);
  EXPECT_EQ(c->latestContactBatch()->seq, 3);
  EXPECT_EQ(c->latestContact()->tick, 29);  // the newest sample of device 1's newest batch
  EXPECT_EQ(c->latestContact()->p_proj_world[0], test::penX(1));
  EXPECT_EQ(c->latestDeviceState()->p_world[0], test::penX(1));
  EXPECT_EQ(c->latestDeviceState(0)->p_world[0], test::penX(0));  // kept, not delivered
  EXPECT_EQ(c->status(Stream::Contact)->messages, 3u);
  EXPECT_EQ(c->status(Stream::Contact)->other_device, 3u);
  EXPECT_EQ(c->counters().other_device, 6u);
}

// ClientOptions::every_device (the live audio client, which plays every pen): both devices'
// batches reach the callback in the order they came, each counted as delivered, none as another
// device's; the same traffic without the option delivers device 0's only.
TEST_F(DeviceClientTest, EveryDeviceDeliversEveryDevicesBatches) {
  test::FakeServer server(lcm_, 11, now_);
  for (bool every : {true, false}) {
    auto c = makeClient(every ? "audio" : "audio0", 0, every);
    Seen batches;
    c->onContactBatch([&](const thx_msgs::contact_batch_t& b, std::int64_t) { batches.emplace_back(b.device, b.seq); });
    c->subscribe(Stream::Contact, 100.0, /*batch=*/true);
    pump(*c);
    ASSERT_TRUE(c->allActive());
    for (std::int64_t seq = 1; seq <= 2; ++seq)
      for (int device : {0, 1}) publish(*c, Stream::Contact, test::contactBatch(device, seq, (seq - 1) * 10));
    pump(*c);
    if (every) {
      EXPECT_EQ(batches, (Seen{{0, 1}, {1, 1}, {0, 2}, {1, 2}}));
      EXPECT_EQ(c->status(Stream::Contact)->messages, 4u);
      EXPECT_EQ(c->status(Stream::Contact)->other_device, 0u);
      EXPECT_EQ(c->counters().other_device, 0u);
      EXPECT_EQ(c->latestContactBatch()->device, 1);  // the newest, whichever device's
      EXPECT_EQ(c->latestContact()->p_proj_world[0], test::penX(1));
    } else {
      EXPECT_EQ(batches, (Seen{{0, 1}, {0, 2}}));
      EXPECT_EQ(c->status(Stream::Contact)->messages, 2u);
      EXPECT_EQ(c->status(Stream::Contact)->other_device, 2u);
      EXPECT_EQ(c->latestContactBatch()->device, 0);
    }
  }
}

// The fake server's own ticks are device 0's (hapticd's publication path): a client following
// device 1 receives 5 s of them and none of its own. The stream is alive, only not its device's:
// no silence, so nothing is asked again.
TEST_F(DeviceClientTest, OtherDevicesTrafficKeepsTheStreamAlive) {
  test::FakeServer server(lcm_, 11, now_);
  auto c = makeClient("visual", 1);
  c->subscribe(Stream::DeviceState, 100.0);
  pump(*c);
  ASSERT_TRUE(c->allActive());
  for (int k = 0; k < 500; ++k) {  // 5 s of 1 kHz ticks: longer than the 3 s silence limit
    server.ticks(k * 10, 10);
    now_ += 10 * kMs;
    pump(*c);
  }
  EXPECT_EQ(c->counters().reconnects, 0u);
  EXPECT_EQ(server.requests, 1);
  EXPECT_EQ(c->status(Stream::DeviceState)->messages, 0u);
  EXPECT_EQ(c->status(Stream::DeviceState)->other_device, 500u);  // 100 Hz for 5 s
  EXPECT_FALSE(c->latestDeviceState());
  ASSERT_TRUE(c->latestDeviceState(0));
  EXPECT_EQ(c->latestDeviceState(0)->tick, 4990);
}

TEST_F(DeviceClientTest, ADeviceIndexOutsideTheTableIsAConfigError) {
  EXPECT_EQ(configErrorOf([&] { makeClient("kit", -1); }), "device -1: expected a device index 0 to 15");
  EXPECT_EQ(configErrorOf([&] { makeClient("kit", client::kMaxDevices); }), "device 16: expected a device index 0 to 15");
}

TEST(DeviceNames, AreTheHellosListInIndexOrder) {
  thx_msgs::hello_t h{};
  h.device_names = "Phantom0,left_hand,pen-3";
  EXPECT_EQ(client::deviceNames(h), (std::vector<std::string>{"Phantom0", "left_hand", "pen-3"}));
  h.device_names = "Phantom0";
  EXPECT_EQ(client::deviceNames(h), (std::vector<std::string>{"Phantom0"}));
  h.device_names = "";
  EXPECT_TRUE(client::deviceNames(h).empty());
}

TEST(DeviceNames, AProblemNamesTheIndexAndTheServersDevices) {
  thx_msgs::hello_t h{};
  h.server_name = "hapticd@lab";
  h.device_names = "Phantom0,Phantom1";
  EXPECT_EQ(client::deviceProblem(h, 0), "");
  EXPECT_EQ(client::deviceProblem(h, 1), "");
  EXPECT_EQ(client::deviceProblem(h, 2),
            "device 2 is not one of hapticd@lab's 2 devices: 0 Phantom0, 1 Phantom1 (hello_t.device_names)");
  h.server_name = "";
  h.device_names = "";  // names nothing: device 0 only
  EXPECT_EQ(client::deviceProblem(h, 0), "");
  EXPECT_EQ(client::deviceProblem(h, 1), "device 1 is not one of hapticd's 1 device: 0 (unnamed) (hello_t.device_names)");
}

class DeviceAppTest : public ::testing::Test {
 protected:
  void SetUp() override { client::clearStopRequest(); }
  void TearDown() override { client::clearStopRequest(); }
  static client::AppOptions options(int device) {
    client::AppOptions o;
    o.client_id = "kit";
    o.lcm_url = "memq://";
    o.connect_timeout_s = 2.0;
    o.client.device = device;
    return o;
  }
  static void hello(client::ClientApp& app) {
    thx_msgs::hello_t h{};
    h.seq = 1;
    h.server_instance = 42;
    h.server_name = "hapticd@test";
    h.device_names = "Phantom0,Phantom1";
    app.lcm().publish(thx_msgs::kChannelHello, &h);
  }
};

TEST_F(DeviceAppTest, WaitForServerAcceptsADeviceTheHelloNames) {
  client::ClientApp app(options(1));
  EXPECT_EQ(app.client().device(), 1);
  hello(app);
  const auto got = app.waitForServer();
  ASSERT_TRUE(got);
  EXPECT_EQ(got->device_names, "Phantom0,Phantom1");
}

TEST_F(DeviceAppTest, WaitForServerRefusesADeviceTheHelloDoesNotName) {
  client::ClientApp app(options(2));
  hello(app);
  EXPECT_EQ(configErrorOf([&] { app.waitForServer(); }),
            "device 2 is not one of hapticd@test's 2 devices: 0 Phantom0, 1 Phantom1 (hello_t.device_names)");
}

}  // namespace test_devices
