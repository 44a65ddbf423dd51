// Each client's streams on a udpm port of its own, requests and heartbeats to a control port
// only hapticd listens on (issue 17, docs/clients.md §6). Deterministic: the port bookkeeping and
// the table with a fake clock; the kernel's delivery by port (a socket bound to one port gets none
// of another port's datagrams, whatever the group); LCM 1.3.1 opening no receive socket for an
// instance that only publishes; and hapticd as a process handing out, recycling and refusing
// ports, checked by what it replies, never by how many messages arrive.
#include <dirent.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <thread>

#include <thx_msgs/lcm_subscribe.hpp>
#include <thx_msgs/protocol.hpp>

#include "base/error.hpp"
#include "thx_client/client.hpp"
#include "server/data_ports.hpp"
#include "server/port_plan.hpp"
#include "server/subscriptions.hpp"
#include "tests/clients/recording_sink.hpp"
#include "tests/support/hapticd_harness.hpp"

namespace test_data_ports {

namespace {

using namespace thx::test;
using thx::srv::DataPorts;
using thx::srv::UdpmUrl;

UdpmUrl bus() { return *thx::srv::parseUdpmUrl("udpm://239.255.76.67:7667?ttl=1"); }

TEST(UdpmUrl, PartsAndOtherPorts) {
  const auto u = thx::srv::parseUdpmUrl("udpm://239.255.76.67:7821?ttl=0&recv_buf_size=4194304");
  ASSERT_TRUE(u);
  EXPECT_EQ(u->group, "239.255.76.67");
  EXPECT_EQ(u->port, 7821);
  EXPECT_EQ(u->withPort(7900), "udpm://239.255.76.67:7900?ttl=0&recv_buf_size=4194304");
  EXPECT_EQ(thx::srv::parseUdpmUrl("udpm://")->withPort(7668), "udpm://239.255.76.67:7668");  // LCM's defaults
  EXPECT_FALSE(thx::srv::parseUdpmUrl("memq://"));
  EXPECT_FALSE(thx::srv::parseUdpmUrl("tcpq://127.0.0.1:7700"));
  EXPECT_FALSE(thx::srv::parseUdpmUrl("udpm://239.255.76.67:99999"));
  EXPECT_FALSE(thx::srv::parseUdpmUrl("udpm://239.255.76.67:7a"));
}

TEST(DataPorts, DistinctPortsRecycledOldestFirstAndARefusalWhenAllAreHeld) {
  DataPorts ports(bus(), 7669, 7671);
  EXPECT_EQ(ports.acquire("a"), 7669);
  EXPECT_EQ(ports.acquire("b"), 7670);
  EXPECT_EQ(ports.acquire("a"), 7669);  // a client keeps its port
  EXPECT_EQ(ports.acquire("c"), 7671);
  EXPECT_EQ(ports.acquire("d"), std::nullopt);
  EXPECT_EQ(ports.exhaustedReason(),
            "no data port free: all 3 ports 7669-7671 are held by clients (hapticd --data-ports)");
  ports.release("b");
  ports.release("a");
  EXPECT_EQ(ports.held(), 1);
  EXPECT_EQ(ports.acquire("d"), 7670);  // released first, taken first
  EXPECT_EQ(ports.acquire("e"), 7669);
  EXPECT_EQ(ports.url(7669), "udpm://239.255.76.67:7669?ttl=1");  // the bus's group and ttl
  ports.release("nobody");                                        // harmless
  EXPECT_THROW(DataPorts(bus(), 7700, 7699), thx::Error);
  EXPECT_THROW(DataPorts(bus(), 0, 10), thx::Error);
}

// The table hands ports out with the first grant, names them in data_url, and takes them back
// when a client leaves or expires; a client beyond the ports is refused and leaves nothing behind.
TEST(DataPorts, TableGrantsRecyclesAndRefuses) {
  thx::srv::SubscriptionLimits limits;
  limits.heartbeat_timeout_ns = 1'000'000'000;
  limits.client_grace_ns = 0;
  thx::srv::SubscriptionTable table(limits);
  DataPorts ports(bus(), 7669, 7670);
  table.useDataPorts(&ports);
  const auto a = table.handleRequest(request("a", "DEVICE_STATE", 60), 0);
  const auto a2 = table.handleRequest(request("a", "CONTACT", 100, true, 2), 0);
  const auto b = table.handleRequest(request("b", "DEVICE_STATE", 60), 0);
  ASSERT_TRUE(a.accepted && a2.accepted && b.accepted);
  EXPECT_EQ(a.data_url, "udpm://239.255.76.67:7669?ttl=1");
  EXPECT_EQ(a2.data_url, a.data_url);  // one port per client, all its streams
  EXPECT_EQ(b.data_url, "udpm://239.255.76.67:7670?ttl=1");

  const auto c = table.handleRequest(request("c", "DEVICE_STATE", 60), 0);
  EXPECT_FALSE(c.accepted);
  EXPECT_EQ(c.reason, "no data port free: all 2 ports 7669-7670 are held by clients (hapticd --data-ports)");
  EXPECT_EQ(c.data_url, "");
  EXPECT_EQ(table.numClients(), 2);

  // a leaves (its last stream unsubscribed): its port is c's now.
  auto unsub = request("a", "DEVICE_STATE", 0, false, 3);
  unsub.action = thx_msgs::subscribe_request_t::ACTION_UNSUBSCRIBE;
  table.handleRequest(unsub, 0);
  EXPECT_EQ(ports.portOf("a"), 7669);  // CONTACT still subscribed
  unsub.stream = "CONTACT";
  unsub.seq = 4;
  table.handleRequest(unsub, 0);
  EXPECT_EQ(ports.portOf("a"), std::nullopt);
  EXPECT_EQ(table.handleRequest(request("c", "DEVICE_STATE", 60, false, 2), 0).data_url,
            "udpm://239.255.76.67:7669?ttl=1");

  // b expires: its port is free for d.
  table.heartbeat([] {
    thx_msgs::heartbeat_t h{};
    h.client_id = "c";
    return h;
  }(), 1'500'000'000);
  EXPECT_EQ(table.expire(1'500'000'000), std::vector<std::string>{"b"});
  EXPECT_EQ(table.handleRequest(request("d", "DEVICE_STATE", 60), 1'500'000'000).data_url,
            "udpm://239.255.76.67:7670?ttl=1");

  // Every stream of a client is sent to its port.
  struct PortSink : RecordingSink {
    using RecordingSink::sendTo;
    std::vector<int> ports_seen;
    void sendTo(int port, const std::string& ch, const thx_msgs::device_state_t& m) override {
      ports_seen.push_back(port);
      send(ch, m);
    }
  } sink;
  runTicks(table, sink, 0, 20);
  ASSERT_FALSE(sink.ports_seen.empty());
  for (std::size_t k = 0; k < sink.states.size(); ++k) {
    EXPECT_EQ(sink.ports_seen[k], sink.states[k].channel == "THX_DEVICE_STATE.c" ? 7669 : 7670);
  }
}

TEST(PortPlan, DefaultsOffAndErrorsThatNameTheValue) {
  const auto p = thx::srv::planPorts("udpm://239.255.76.67:7667?ttl=1", 32, "", "");
  EXPECT_EQ(p.control_port, 7668);
  EXPECT_EQ(p.controlUrl(), "udpm://239.255.76.67:7668?ttl=1");
  EXPECT_EQ(p.data_first, 7669);
  EXPECT_EQ(p.data_last, 7700);
  const auto off = thx::srv::planPorts("udpm://239.255.76.67:7667?ttl=1", 32, "off", "off");
  EXPECT_EQ(off.control_port, 0);
  EXPECT_EQ(off.data_first, 0);
  const auto memq = thx::srv::planPorts("memq://", 32, "", "");
  EXPECT_FALSE(memq.bus);
  EXPECT_EQ(memq.controlUrl(), "");
  auto error = [](const std::string& control, const std::string& data) {
    try {
      thx::srv::planPorts("udpm://239.255.76.67:7667?ttl=0", 32, control, data);
    } catch (const thx::UsageError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error("", "7660-7670"),
            "--data-ports 7660-7670: holds the bus port 7667 of --lcm-url; expected a range apart from it");
  EXPECT_EQ(error("", "7668-7670"),
            "--data-ports 7668-7670: holds the control port 7668; expected a range apart from it (or another "
            "--control-port)");
  EXPECT_EQ(error("", "7800-7700"),
            "--data-ports 7800-7700: expected FIRST-LAST (ports 1..65535, FIRST <= LAST), one port, or 'off'");
  EXPECT_EQ(error("x", ""), "--control-port x: expected a port 1..65535 or 'off'");
  EXPECT_EQ(error("7667", ""), "--control-port 7667: is the bus port of --lcm-url; expected another port");
  EXPECT_THROW(thx::srv::planPorts("tcpq://127.0.0.1:7700", 32, "", "7800-7810"), thx::UsageError);
}

// Sockets this process holds (entries of /proc/self/fd that are sockets).
int openSockets() {
  int n = 0;
  DIR* d = opendir("/proc/self/fd");
  if (!d) return -1;
  while (dirent* e = readdir(d)) {
    struct stat st {};
    if (fstatat(dirfd(d), e->d_name, &st, 0) == 0 && S_ISSOCK(st.st_mode)) ++n;
  }
  closedir(d);
  return n;
}

class DataPortsLoopback : public HapticdProcessTest {
 protected:
  int basePort() const { return std::atoi(url_.c_str() + url_.rfind(':') + 1); }
  std::string portUrl(int port) const { return thx::srv::parseUdpmUrl(url_)->withPort(port); }
};

// What hapticd's data LCMs and a client's control LCM rely on: an LCM that only publishes has its
// send socket and no receive socket (no receive thread waking for the port's traffic). Subscribing
// adds the receive socket.
TEST_F(DataPortsLoopback, AnLcmThatOnlyPublishesOpensNoReceiveSocket) {
  if (!udpmAvailable()) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  const int before = openSockets();
  lcm::LCM sender(portUrl(basePort() + 30));
  ASSERT_TRUE(sender.good());
  const char bytes[8] = {};
  for (int k = 0; k < 10; ++k) sender.publish("THX_TEST", bytes, sizeof bytes);
  EXPECT_EQ(openSockets(), before + 1);  // the send socket only
  lcm::LCM receiver(portUrl(basePort() + 31));
  receiver.subscribeFunction("THX_TEST", +[](const lcm::ReceiveBuffer*, const std::string&, void*) {}, (void*)nullptr);
  EXPECT_EQ(openSockets(), before + 3);  // its send socket and, subscribed, its receive socket
}

// The kernel delivers a datagram only to sockets bound to its port: a process listening on
// another client's port (same group, even subscribed to every channel) receives none of it.
TEST_F(DataPortsLoopback, AClientOnAnotherPortReceivesNoneOfTheDatagrams) {
  if (!udpmAvailable()) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  struct Count {
    int n = 0;
    void on(const lcm::ReceiveBuffer*, const std::string&) { ++n; }
  } mine, other;
  lcm::LCM own(portUrl(basePort() + 32)), elsewhere(portUrl(basePort() + 33)), sender(portUrl(basePort() + 32));
  ASSERT_TRUE(own.good() && elsewhere.good() && sender.good());
  own.subscribe(".*", &Count::on, &mine)->setQueueCapacity(1000);  // LCM's default 30 would cut the burst
  elsewhere.subscribe(".*", &Count::on, &other)->setQueueCapacity(1000);
  const char bytes[64] = {};
  constexpr int kSent = 50;
  for (int k = 0; k < kSent; ++k) sender.publish("THX_DEVICE_STATE.mine", bytes, sizeof bytes);
  // They reach the port they were sent to (ttl=0 loopback, a few kB)...
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (mine.n < kSent && std::chrono::steady_clock::now() < give_up) own.handleTimeout(10);
  EXPECT_GT(mine.n, 0);
  // ...and by then the other port's socket has had every chance to see one: it holds nothing.
  pollfd p{elsewhere.getFileno(), POLLIN, 0};
  EXPECT_EQ(poll(&p, 1, 100), 0);
  EXPECT_EQ(elsewhere.handleTimeout(0), 0);
  EXPECT_EQ(other.n, 0);
}

// The kit's side, against a hand-made server over udpm (no hapticd): requests go to the bus until
// a hello names a control URL, then to that; the stream is received on the URL the reply names;
// after a restart that names another data URL the kit listens there instead. Each step waits for
// the message it needs (up to 20 s); nothing counts arrivals.
TEST_F(DataPortsLoopback, TheKitSendsToTheControlUrlAndListensOnTheDataUrlTheServerNames) {
  if (!udpmAvailable()) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  const int p = basePort();
  lcm::LCM bus(url_), control(portUrl(p + 1)), data1(portUrl(p + 2)), data2(portUrl(p + 3));
  ASSERT_TRUE(bus.good() && control.good() && data1.good() && data2.good());
  struct Requests {
    std::vector<thx_msgs::subscribe_request_t> got;
    void on(const lcm::ReceiveBuffer* rbuf, const std::string&) {
      thx_msgs::subscribe_request_t r;
      if (thx_msgs::try_decode(rbuf->data, rbuf->data_size, r) > 0) got.push_back(r);
    }
  } on_bus, on_control;
  lcm::LCM server_bus(url_);  // the server's own socket on the bus
  server_bus.subscribe(thx_msgs::kChannelSubscribe, &Requests::on, &on_bus);
  control.subscribe(thx_msgs::kChannelSubscribe, &Requests::on, &on_control);

  thx::client::Client client(bus, "kit");
  client.subscribe(thx_msgs::Stream::DeviceState, 100);
  auto until = [&](const std::function<bool()>& done) {
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!done() && std::chrono::steady_clock::now() < give_up) {
      client.poll(1);
      server_bus.handleTimeout(0);
      control.handleTimeout(0);
    }
    return done();
  };
  // Before any hello: the request comes on the bus.
  ASSERT_TRUE(until([&] { return !on_bus.got.empty(); }));
  auto hello = [&](std::int64_t instance) {
    thx_msgs::hello_t h{};
    h.server_instance = instance;
    h.protocol_version = thx_msgs::hello_t::PROTOCOL_VERSION;
    h.control_url = portUrl(p + 1);
    server_bus.publish(thx_msgs::kChannelHello, &h);
  };
  auto reply = [&](const thx_msgs::subscribe_request_t& r, std::int64_t instance, int data_port) {
    thx_msgs::subscribe_reply_t a{};
    a.server_instance = instance;
    a.request_seq = r.seq;
    a.client_id = r.client_id;
    a.stream = r.stream;
    a.action = r.action;
    a.accepted = 1;
    a.rate_hz = 100;
    a.channel = "THX_DEVICE_STATE.kit";
    a.heartbeat_timeout_us = 2'000'000;
    a.data_url = portUrl(data_port);
    server_bus.publish(thx_msgs::kChannelSubscribeReply, &a);
  };
  auto stateOn = [&](lcm::LCM& l, std::int64_t tick) {
    thx_msgs::device_state_t d{};
    d.tick = tick;
    l.publish("THX_DEVICE_STATE.kit", &d);
  };
  // The hello names the control URL: the request, sent again at once now that the server is
  // known to be up, goes there, not to the bus.
  hello(11);
  ASSERT_TRUE(until([&] { return !on_control.got.empty(); }));
  EXPECT_EQ(client.controlUrl(), portUrl(p + 1));
  const std::size_t on_bus_before = on_bus.got.size();
  reply(on_control.got.back(), 11, p + 2);
  ASSERT_TRUE(until([&] { return client.allActive(); }));
  EXPECT_EQ(client.dataUrl(), portUrl(p + 2));
  EXPECT_EQ(client.status(thx_msgs::Stream::DeviceState)->data_url, portUrl(p + 2));
  // Data on the bus or another port does not reach it; data on its port does.
  stateOn(bus, 1);
  stateOn(data2, 2);
  stateOn(data1, 3);
  ASSERT_TRUE(until([&] { return client.latestDeviceState().has_value(); }));
  EXPECT_EQ(client.latestDeviceState()->tick, 3);
  EXPECT_EQ(on_bus.got.size(), on_bus_before);  // nothing more on the bus once the control URL is known

  // A restarted server (new instance) gives it another port: the kit moves there.
  const std::size_t asked = on_control.got.size();
  hello(22);
  ASSERT_TRUE(until([&] { return on_control.got.size() > asked; }));
  reply(on_control.got.back(), 22, p + 3);
  ASSERT_TRUE(until([&] { return client.dataUrl() == portUrl(p + 3); }));
  stateOn(data2, 40);
  ASSERT_TRUE(until([&] { return client.latestDeviceState()->tick == 40; }));
  EXPECT_EQ(client.counters().link_errors, 0u);
}

// hapticd as a process with two data ports: two clients get distinct ports (named in the log and
// replies), a third is refused naming the range, and once the first has left its port is the
// third's. Ordered by the server's log lines, so no timing is asserted. a holds its port for 5 s
// from its first message, so that c asks while a and b both hold theirs even when the VM is slow
// to start c (with 1 s, a starved test could start c after a had left, and c was granted).
TEST_F(DataPortsLoopback, HapticdHandsOutRecyclesAndRefusesPorts) {
  if (!udpmAvailable()) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  const int p = basePort();
  const std::string range = std::to_string(p + 2) + "-" + std::to_string(p + 3);
  startServer({"--data-ports", range});
  const pid_t a = startProbe("a", {"--stream", "DEVICE_STATE", "--rate", "100", "--duration", "5"});
  ASSERT_TRUE(serverLogHas("client a: DEVICE_STATE at 100 Hz on THX_DEVICE_STATE.a at ", 30)) << serverLog();
  const pid_t b = startProbe("b", {"--stream", "DEVICE_STATE", "--rate", "100", "--duration", "30"});
  ASSERT_TRUE(serverLogHas("client b: DEVICE_STATE at 100 Hz on THX_DEVICE_STATE.b at ", 30)) << serverLog();
  const std::string log = serverLog();
  const std::string a_url = portUrl(p + 2), b_url = portUrl(p + 3);
  EXPECT_NE(log.find("on THX_DEVICE_STATE.a at " + a_url), std::string::npos) << log;
  EXPECT_NE(log.find("on THX_DEVICE_STATE.b at " + b_url), std::string::npos) << log;
  // c while a and b hold both ports: refused with the reason (probe-client exits 1).
  const pid_t c = startProbe("c", {"--stream", "DEVICE_STATE", "--rate", "100", "--duration", "1"});
  EXPECT_EQ(finishProbe(c, 60), 1) << slurp(path("c.err"));
  EXPECT_EQ(jsonField(probeJson("c"), "state"), "refused");
  EXPECT_EQ(jsonField(probeJson("c"), "reason"),
            "no data port free: all 2 ports " + range + " are held by clients (hapticd --data-ports)");
  // a finishes and unsubscribes; the next client gets its port.
  EXPECT_EQ(finishProbe(a, 60), 0) << slurp(path("a.err"));
  ASSERT_TRUE(serverLogHas("client a: DEVICE_STATE unsubscribed", 30)) << serverLog();
  const pid_t d = startProbe("d", {"--stream", "DEVICE_STATE", "--rate", "100", "--duration", "1"});
  EXPECT_EQ(finishProbe(d, 60), 0) << slurp(path("d.err"));
  EXPECT_NE(serverLog().find("on THX_DEVICE_STATE.d at " + a_url), std::string::npos) << serverLog();
  expectStreamFlowed(probeJson("a"));
  expectStreamFlowed(probeJson("d"));
  kill(b, SIGTERM);
  finishProbe(b, 30);
  EXPECT_EQ(stopServer(), 0) << serverLog();
}

// A UDP socket bound without SO_REUSEADDR, as every LCM publisher's ephemeral send socket is:
// while it lives, LCM cannot bind a receive socket to its port.
class PortHolder {
 public:
  explicit PortHolder(int port) : fd_(::socket(AF_INET, SOCK_DGRAM, 0)) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(std::uint16_t(port));
    a.sin_addr.s_addr = htonl(INADDR_ANY);
    held_ = fd_ >= 0 && ::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  }
  ~PortHolder() { release(); }
  bool held() const { return held_; }
  void release() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

 private:
  int fd_;
  bool held_ = false;
};

struct Ignore {
  void on(const lcm::ReceiveBuffer*, const std::string&) {}
};

// LCM's C++ subscribe() returns a Subscription even when its receive socket did not bind (and the
// first setQueueCapacity() on it would read through null); subscribeUntyped says nullptr. Once the
// port is free, the same LCM binds on the next subscribe.
TEST_F(DataPortsLoopback, ASubscriptionOnAPortAnotherProgramHoldsIsNull) {
  if (!udpmAvailable()) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  PortHolder holder(basePort() + 34);
  ASSERT_TRUE(holder.held());
  lcm::LCM lcm(portUrl(basePort() + 34));
  ASSERT_TRUE(lcm.good());
  Ignore ignore;
  EXPECT_EQ(thx_msgs::subscribeUntyped(lcm, "THX_TEST", &Ignore::on, &ignore, 64), nullptr);
  holder.release();
  EXPECT_NE(thx_msgs::subscribeUntyped(lcm, "THX_TEST", &Ignore::on, &ignore, 64), nullptr);
}

// The CI failure this guards: a server names a data URL whose port another program holds. The kit
// does not crash; it counts a link error naming the URL and the cause, and stays pending for data.
TEST_F(DataPortsLoopback, AClientWhoseDataPortIsHeldNamesItAndGoesOn) {
  if (!udpmAvailable()) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  const int p = basePort();
  PortHolder holder(p + 35);
  ASSERT_TRUE(holder.held());
  lcm::LCM bus(url_), server_bus(url_);
  ASSERT_TRUE(bus.good() && server_bus.good());
  struct Requests {
    std::vector<thx_msgs::subscribe_request_t> got;
    void on(const lcm::ReceiveBuffer* rbuf, const std::string&) {
      thx_msgs::subscribe_request_t r;
      if (thx_msgs::try_decode(rbuf->data, rbuf->data_size, r) > 0) got.push_back(r);
    }
  } requests;
  ASSERT_NE(thx_msgs::subscribeUntyped(server_bus, thx_msgs::kChannelSubscribe, &Requests::on, &requests), nullptr);
  thx::client::Client client(bus, "held");
  client.subscribe(thx_msgs::Stream::DeviceState, 100);
  auto until = [&](const std::function<bool()>& done) {
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!done() && std::chrono::steady_clock::now() < give_up) {
      client.poll(1);
      server_bus.handleTimeout(0);
    }
    return done();
  };
  ASSERT_TRUE(until([&] { return !requests.got.empty(); }));
  thx_msgs::subscribe_reply_t a{};
  a.server_instance = 7;
  a.request_seq = requests.got.back().seq;
  a.client_id = "held";
  a.stream = "DEVICE_STATE";
  a.action = requests.got.back().action;
  a.accepted = 1;
  a.rate_hz = 100;
  a.channel = "THX_DEVICE_STATE.held";
  a.heartbeat_timeout_us = 2'000'000;
  a.data_url = portUrl(p + 35);
  server_bus.publish(thx_msgs::kChannelSubscribeReply, &a);
  ASSERT_TRUE(until([&] { return client.counters().link_errors > 0; }));
  EXPECT_NE(client.lastLinkError().find(portUrl(p + 35)), std::string::npos) << client.lastLinkError();
  EXPECT_NE(client.lastLinkError().find("did not bind"), std::string::npos) << client.lastLinkError();
}

}  // namespace

}  // namespace test_data_ports
