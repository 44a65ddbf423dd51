// Our encoder talking to our decoder over real TCP sockets on 127.0.0.1 (ephemeral ports):
// handshake, reports, commands, several clients, a peer that closes mid-message, and a peer
// that sends garbage, which drops that connection only.
//
// The loops wait with poll(2) and give up after a generous safety deadline; nothing asserts on
// timing.
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/socket.h>

#include <chrono>
#include <functional>
#include <memory>

#include "device/vrpn/base_messages.hpp"
#include "device/vrpn/button_messages.hpp"
#include "device/vrpn/force_messages.hpp"
#include "device/vrpn/tcp_connection.hpp"
#include "device/vrpn/tracker_messages.hpp"
#include "tests/vrpn/endpoint_harness.hpp"

namespace test_tcp_loopback {

using namespace thx::vrpn;
using namespace thx::vrpn::harness;

namespace {

constexpr auto kSafetyDeadline = std::chrono::seconds(20);

struct Listener {
  UniqueFd fd;
  std::uint16_t port = 0;
  Listener() {
    Result<UniqueFd> l = listenTcp("127.0.0.1", 0);
    EXPECT_TRUE(l) << l.error().reason;
    if (!l) return;
    fd = std::move(l).value();
    port = localPort(fd.get());
  }
  std::unique_ptr<TcpConnection> accept(Endpoint::Options o = fixedClock()) {
    Result<UniqueFd> a = acceptTcp(fd.get());
    EXPECT_TRUE(a) << a.error().reason;
    if (!a || !*a) return nullptr;
    return std::make_unique<TcpConnection>(std::move(a).value(), std::move(o));
  }
};

std::unique_ptr<TcpConnection> connectTo(std::uint16_t port) {
  Result<UniqueFd> c = connectTcp("127.0.0.1", port);
  EXPECT_TRUE(c) << c.error().reason;
  return std::make_unique<TcpConnection>(std::move(c).value(), fixedClock());
}

// Pumps every open connection and hands each event to `on_event` until `done` or the deadline.
bool runUntil(
    std::vector<TcpConnection*> conns, const std::function<void(TcpConnection&, const Event&)>& on_event,
    const std::function<bool()>& done, int listen_fd = -1, const std::function<void()>& on_accept = [] {}) {
  const auto deadline = std::chrono::steady_clock::now() + kSafetyDeadline;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::vector<pollfd> fds;
    if (listen_fd >= 0) fds.push_back(pollfd{listen_fd, POLLIN, 0});
    for (TcpConnection* c : conns)
      if (c->open()) fds.push_back(pollfd{c->fd(), short(POLLIN | (c->wantsWrite() ? POLLOUT : 0)), 0});
    ::poll(fds.data(), fds.size(), 10);
    if (listen_fd >= 0 && (fds[0].revents & POLLIN)) on_accept();
    for (TcpConnection* c : conns) {
      c->pump();
      while (auto ev = c->endpoint().poll()) on_event(*c, *ev);
    }
  }
  return true;
}

// A raw socket connected to `listener`, and the served side of it.
void rawPeer(Listener& listener, UniqueFd& raw, std::unique_ptr<TcpConnection>& served) {
  Result<UniqueFd> connected = connectTcp("127.0.0.1", listener.port);
  ASSERT_TRUE(connected);
  raw = std::move(connected).value();
  ASSERT_TRUE(runUntil(
      {}, [](TcpConnection&, const Event&) {}, [&] { return served != nullptr; }, listener.fd.get(),
      [&] { served = listener.accept(); }));
}

}  // namespace

TEST(TcpLoopback, ServerAndClientExchangeEverything) {
  Listener listener;
  std::unique_ptr<TcpConnection> client = connectTo(listener.port);
  std::unique_ptr<TcpConnection> server;
  // The accept happens inside the loop, as in a real server.
  std::vector<TcpConnection*> conns{client.get()};

  const std::int32_t c_dev = client->endpoint().addSender("Phantom0");
  for (auto n : {Pong::kTypeName, ButtonStates::kTypeName, TrackerPosQuat::kTypeName}) client->endpoint().addType(n);
  std::int32_t s_dev = kNoId;

  constexpr int kReports = 2000;
  int reports_seen = 0;
  bool states_seen = false, pong_seen = false, plane_seen = false;
  ForcePlane plane;
  plane.plane = {0.0f, 0.0f, 1.0f, 0.01f};
  plane.kspring = 0.5f;
  plane.n_rec_cycles = 10;

  auto on_event = [&](TcpConnection& c, const Event& ev) {
    if (std::holds_alternative<Dropped>(ev)) ADD_FAILURE() << summary(ev) << ": " << std::get<Dropped>(ev).error.reason;
    const bool is_server = &c == server.get();
    if (std::holds_alternative<Connected>(ev)) {
      if (is_server) {
        ASSERT_TRUE(c.endpoint().sendMessage(s_dev, ButtonStates{{0, 1}}));
      } else {
        ASSERT_TRUE(c.endpoint().sendMessage(c_dev, Ping{}));
        ASSERT_TRUE(c.endpoint().sendMessage(c_dev, plane));
      }
      return;
    }
    const auto* m = std::get_if<UserMessage>(&ev);
    if (!m) return;
    if (is_server) {
      if (m->type_name == Ping::kTypeName) {
        ASSERT_TRUE(c.endpoint().sendMessage(s_dev, Pong{}));
        for (int i = 0; i < kReports; ++i) {
          TrackerPosQuat r;
          r.pos = {0.001 * i, 0.0, 0.0};
          ASSERT_TRUE(c.endpoint().sendMessage(s_dev, r, TimeValue{std::uint32_t(i), 0}));
        }
      } else if (m->type_name == ForcePlane::kTypeName) {
        Result<ForcePlane> p = ForcePlane::decode(m->payload);
        ASSERT_TRUE(p);
        EXPECT_EQ(*p, plane);
        plane_seen = true;
      }
    } else {
      if (m->type_name == ButtonStates::kTypeName) {
        EXPECT_EQ(ButtonStates::decode(m->payload)->states, (std::vector<std::int32_t>{0, 1}));
        states_seen = true;
      } else if (m->type_name == Pong::kTypeName) {
        pong_seen = true;
      } else if (m->type_name == TrackerPosQuat::kTypeName) {
        Result<TrackerPosQuat> r = TrackerPosQuat::decode(m->payload);
        ASSERT_TRUE(r);
        EXPECT_EQ(m->header.time.sec, std::uint32_t(reports_seen));  // in order, none lost
        EXPECT_DOUBLE_EQ(r->pos[0], 0.001 * reports_seen);
        ++reports_seen;
      }
    }
  };
  auto on_accept = [&] {
    server = listener.accept();
    ASSERT_TRUE(server);
    s_dev = server->endpoint().addSender("Phantom0");
    for (auto n : {Ping::kTypeName, ForcePlane::kTypeName}) server->endpoint().addType(n);
    conns.push_back(server.get());
  };
  // conns grows inside on_accept; runUntil copies the vector, so re-enter once the server exists.
  ASSERT_TRUE(runUntil(
      conns, on_event, [&] { return server != nullptr; }, listener.fd.get(), on_accept));
  ASSERT_TRUE(runUntil(conns, on_event, [&] { return reports_seen == kReports && plane_seen; }));
  EXPECT_TRUE(states_seen);
  EXPECT_TRUE(pong_seen);
  EXPECT_EQ(server->endpoint().state(), Endpoint::State::kConnected);
  EXPECT_EQ(client->endpoint().state(), Endpoint::State::kConnected);

  // The client leaves: the server sees a clean close.
  client->close(Error{ErrorCode::kPeerClosed, "test done"});
  std::vector<std::string> server_events;
  ASSERT_TRUE(runUntil(
      {server.get()}, [&](TcpConnection&, const Event& ev) { server_events.push_back(summary(ev)); },
      [&] { return !server->open() && server->endpoint().state() == Endpoint::State::kDropped; }));
  EXPECT_EQ(server_events, (std::vector<std::string>{"dropped peer closed"}));
  EXPECT_EQ(server->closeReason()->code, ErrorCode::kPeerClosed);
}

TEST(TcpLoopback, GarbageFromOneClientDropsOnlyThatClient) {
  Listener listener;
  std::unique_ptr<TcpConnection> good = connectTo(listener.port);
  Result<UniqueFd> raw = connectTcp("127.0.0.1", listener.port);
  ASSERT_TRUE(raw);

  std::vector<std::unique_ptr<TcpConnection>> served;
  auto accept_all = [&] {
    while (auto c = listener.accept()) {
      c->endpoint().addSender("Phantom0");
      served.push_back(std::move(c));
    }
  };
  ASSERT_TRUE(runUntil(
      {good.get()}, [](TcpConnection&, const Event&) {}, [&] { return served.size() == 2; }, listener.fd.get(),
      accept_all));

  // The raw client sends a valid cookie, then a header claiming a 1 GB message.
  Bytes evil;
  const Cookie cookie = makeCookie();
  evil.assign(cookie.begin(), cookie.end());
  ByteWriter w(evil);
  w.u32(0x40000000);
  w.zeros(20);
  ASSERT_EQ(::send(raw->get(), evil.data(), evil.size(), MSG_NOSIGNAL), ssize_t(evil.size()));

  std::vector<std::string> events;
  auto on_event = [&](TcpConnection& c, const Event& ev) {
    events.push_back(std::to_string(&c == good.get() ? -1 : int(&c == served[0].get() ? 0 : 1)) + " " + summary(ev));
  };
  ASSERT_TRUE(runUntil({good.get(), served[0].get(), served[1].get()}, on_event,
                       [&] { return !served[0]->open() || !served[1]->open(); }));
  // Exactly one served connection died, with the size reason; the other and the good client live.
  const int evil_index = served[0]->open() ? 1 : 0;
  EXPECT_FALSE(served[std::size_t(evil_index)]->open());
  EXPECT_EQ(served[std::size_t(evil_index)]->closeReason()->code, ErrorCode::kLengthTooLarge);
  EXPECT_TRUE(served[std::size_t(1 - evil_index)]->open());
  EXPECT_TRUE(good->open());
  EXPECT_EQ(good->endpoint().state(), Endpoint::State::kConnected);
  EXPECT_EQ(served[std::size_t(1 - evil_index)]->endpoint().state(), Endpoint::State::kConnected);
}

TEST(TcpLoopback, PeerClosingMidMessageIsTruncation) {
  Listener listener;
  UniqueFd raw;
  std::unique_ptr<TcpConnection> served;
  ASSERT_NO_FATAL_FAILURE(rawPeer(listener, raw, served));
  Bytes partial;
  const Cookie cookie = makeCookie();
  partial.assign(cookie.begin(), cookie.end());
  const Bytes desc = senderDesc(1, "Tracker0");
  partial.insert(partial.end(), desc.begin(), desc.end() - 5);
  ASSERT_EQ(::send(raw.get(), partial.data(), partial.size(), MSG_NOSIGNAL), ssize_t(partial.size()));
  raw.reset();

  std::vector<std::string> events;
  ASSERT_TRUE(runUntil(
      {served.get()}, [&](TcpConnection&, const Event& ev) { events.push_back(summary(ev)); },
      [&] { return served->endpoint().state() == Endpoint::State::kDropped && !served->open(); }));
  EXPECT_EQ(events, (std::vector<std::string>{"connected log=0 minor_differs=0", "dropped truncated"}));
}

// A peer that closes with our bytes unread makes its kernel reset the connection (a stock
// client quitting while 1 kHz reports are in flight): that is the peer's close, not an error.
TEST(TcpLoopback, APeerThatResetsTheConnectionHasClosedIt) {
  Listener listener;
  UniqueFd raw;
  std::unique_ptr<TcpConnection> served;
  ASSERT_NO_FATAL_FAILURE(rawPeer(listener, raw, served));
  const Cookie cookie = makeCookie();
  ASSERT_EQ(::send(raw.get(), cookie.data(), cookie.size(), MSG_NOSIGNAL), ssize_t(cookie.size()));
  // The served side handshakes and sends its cookie and descriptions, which the peer never reads.
  std::vector<std::string> events;
  const auto collect = [&](TcpConnection&, const Event& ev) { events.push_back(summary(ev)); };
  ASSERT_TRUE(runUntil({served.get()}, collect, [&] {
    return served->endpoint().state() == Endpoint::State::kConnected && !served->wantsWrite();
  }));
  // Closed only once those bytes wait in its receive queue: then its kernel resets the connection
  // (closed before they arrive, it would close it in order).
  pollfd readable{raw.get(), POLLIN, 0};
  ASSERT_EQ(::poll(&readable, 1, 20000), 1);
  raw.reset();
  ASSERT_TRUE(runUntil({served.get()}, collect, [&] { return !served->open(); }));
  ASSERT_TRUE(served->closeReason().has_value());
  EXPECT_EQ(served->closeReason()->code, ErrorCode::kPeerClosed);
  EXPECT_EQ(served->closeReason()->reason, "peer reset the connection");
  EXPECT_EQ(events, (std::vector<std::string>{"connected log=0 minor_differs=0", "dropped peer closed"}));
}

TEST(TcpLoopback, ConnectionRefusedIsASocketError) {
  // Bind a port, then close it, so nothing listens there.
  std::uint16_t port = 0;
  {
    Listener l;
    port = l.port;
  }
  std::unique_ptr<TcpConnection> c = connectTo(port);
  ASSERT_TRUE(runUntil(
      {c.get()}, [](TcpConnection&, const Event&) {}, [&] { return !c->open(); }));
  EXPECT_EQ(c->closeReason()->code, ErrorCode::kSocket);
}

}  // namespace test_tcp_loopback
