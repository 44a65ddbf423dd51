#pragma once
// The VRPN server test rig shared by test_server_loopback.cpp and test_server_interop.cpp:
// hapticd's VRPN server (server/vrpn_server.hpp) on 127.0.0.1 with the real servo pipeline
// behind it, a pen held by the test (HeldPen, paced at 1 ms on the monotonic clock, far above
// the texture, so every force it feels comes from VRPN effects), and a raw protocol client whose
// every byte the test controls (RawClient). Header-only, for tests only.
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/socket.h>

#include <atomic>
#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "rt/clock.hpp"
#include "device/device_specs.hpp"
#include "rt/pacer.hpp"
#include "device/vrpn/base_messages.hpp"
#include "device/vrpn/button_messages.hpp"
#include "device/vrpn/force_messages.hpp"
#include "device/vrpn/tcp_connection.hpp"
#include "device/vrpn/tracker_messages.hpp"
#include "device/vrpn/tracker_transform_messages.hpp"
#include "device/vrpn/udp_socket.hpp"
#include "device/vrpn/vrpn_client_device.hpp"
#include "server/servo_rig.hpp"
#include "tests/support/servo_inputs.hpp"
#include "server/vrpn_server.hpp"
#include "tests/vrpn/transcripts.hpp"
#include "textures/generators.hpp"

namespace thx::vrpn::test {

using namespace std::chrono_literals;

inline constexpr auto kDeadline = std::chrono::seconds(20);

template <class Pred>
bool eventually(Pred pred, std::chrono::milliseconds step = 5ms) {
  const auto until = std::chrono::steady_clock::now() + kDeadline;
  while (std::chrono::steady_clock::now() < until) {
    if (pred()) return true;
    std::this_thread::sleep_for(step);
  }
  return pred();
}

// Device time that never falls behind: each tick's deadline comes one period after the last and
// is waited for in real time (so the servo ticks at about 1 kHz on a quiet machine), but a late
// wake-up moves device time only to the deadline, never past it. On a loaded machine the servo
// ticks more slowly instead of missing ticks: a missed-tick fault ramps the force down and in
// again, which made tests that wait for a commanded force fail by chance (three did, in the
// sanitizer tree with both cores busy). What these tests check is the protocol, not the timing.
class NeverLateClock final : public rt::Clock {
 public:
  std::int64_t nowNs() override { return now_ns_; }
  void sleepUntilNs(std::int64_t t_ns) override {
    if (t_ns <= now_ns_) return;
    std::this_thread::sleep_for(std::chrono::nanoseconds(t_ns - now_ns_));
    now_ns_ = t_ns;
  }

 private:
  std::int64_t now_ns_ = rt::monotonicNowNs();
};

// A pen the test holds at a settable position; keeps what the servo last wrote.
class HeldPen final : public dev::HapticDevice {
 public:
  HeldPen() : spec_(dev::phantomDesktopSpec()), pacer_(clock_, 1'000'000) {}
  const dev::DeviceSpec& spec() const override { return spec_; }
  dev::OutputMode outputMode() const override { return dev::OutputMode::Force; }
  void open() override { pacer_.start(); }
  void close() override {}
  dev::DeviceState read() override {
    dev::DeviceState s;
    s.timing = pacer_.wait();
    std::lock_guard lock(mutex_);
    s.p_world = pos_;
    s.buttons = buttons_;
    s.valid = valid_;
    return s;
  }
  void write(const dev::DeviceCommand& c) override {
    std::lock_guard lock(mutex_);
    force_ = c.forces_enabled ? c.force_world_n : Eigen::Vector3d::Zero();
  }
  void hold(const Eigen::Vector3d& p) {
    std::lock_guard lock(mutex_);
    pos_ = p;
  }
  void setButtons(std::uint32_t b) {
    std::lock_guard lock(mutex_);
    buttons_ = b;
  }
  // An invalid reading, like a VRPN device before its first pose or a glitching encoder.
  void setValid(bool v) {
    std::lock_guard lock(mutex_);
    valid_ = v;
  }
  Eigen::Vector3d force() {
    std::lock_guard lock(mutex_);
    return force_;
  }

 private:
  dev::DeviceSpec spec_;
  NeverLateClock clock_;
  rt::Pacer pacer_;
  std::mutex mutex_;
  Eigen::Vector3d pos_{0.0, 0.0, 0.05};  // 5 cm above the textured plane z = 0
  Eigen::Vector3d force_ = Eigen::Vector3d::Zero();
  std::uint32_t buttons_ = 0;
  bool valid_ = true;
};

// What the served rig's servo is built on: the pen and a sine normal map (a base, so that it
// exists before the servo).
struct ServedRigInputs {
  explicit ServedRigInputs(bool pen_valid) : texture(sine(), /*relief=*/false) { pen.setValid(pen_valid); }
  static tex::GenerateRequest sine() {
    tex::GenerateRequest g;
    g.kind = "sine";
    g.size = 64;
    return g;
  }

  HeldPen pen;
  ::thx::test::GeneratedSurface texture;
};

// A held pen behind the servo pipeline as hapticd wires it (server/servo_rig.hpp), its VRPN
// effects renderer attached and its snapshots published for a VRPN server; startTicking() runs the
// servo on a thread of its own until the pen is destroyed.
struct ServedPen : ServedRigInputs, srv::ServoRig {
  explicit ServedPen(bool pen_valid = true)
      : ServedRigInputs(pen_valid), srv::ServoRig(pen, *texture.surface, ::thx::test::unitTestWiring(500.0)) {
    servo().attachExternalEffects(&effects);
    snapshots = &servo().publishSnapshots();
  }
  ~ServedPen() { stopTicking(); }
  void startTicking() {
    pen.open();
    thread = std::thread([this] {
      while (!stop.load()) {
        const srv::TickRecord& t = tickAndDrain();
        max_missed = std::max<std::int64_t>(max_missed, t.missed);
        ticks.store(t.tick);
      }
    });
  }
  void stopTicking() {
    stop.store(true);
    if (thread.joinable()) thread.join();
  }
  // The effect limits of this pen's device, as hapticd gives them to its VRPN server.
  void limit(srv::VrpnServerOptions& options) const {
    options.limits.max_stiffness_n_per_m = pen.spec().max_stiffness_n_per_m;
    options.limits.peak_force_n = pen.spec().peak_force_n;
  }

  srv::ExternalEffectRenderer effects{1e-3};
  const rt::LatestSlot<srv::DeviceSnapshot>* snapshots = nullptr;
  std::atomic<bool> stop{false};
  std::atomic<std::int64_t> ticks{0};
  std::int64_t max_missed = 0;  // written by the servo thread, read after stopTicking()
  std::thread thread;
};

// One served pen with a VRPN server of its own, named Phantom0.
struct ServedRig : ServedPen {
  explicit ServedRig(srv::VrpnServerOptions options = {}, std::uint16_t port = 0, bool pen_valid = true)
      : ServedPen(pen_valid) {
    options.port = port;
    options.log = false;
    limit(options);
    server = std::make_unique<srv::VrpnServer>(*snapshots, &effects, options);
    server->start();
    startTicking();
  }
  ~ServedRig() {
    stopTicking();
    server->stop();
  }
  std::uint16_t port() const { return server->port(); }
  std::string tcpAddress() const { return "Phantom0@tcp://127.0.0.1:" + std::to_string(port()); }
  std::string lobAddress() const { return "Phantom0@127.0.0.1:" + std::to_string(port()); }

  std::unique_ptr<srv::VrpnServer> server;
};

inline vrpn::VrpnClientOptions fastClient() {
  vrpn::VrpnClientOptions o;
  o.reconnect_interval = 100ms;
  o.staleness = 200ms;  // sanitizer builds on a busy VM: we test the data, not the latency
  o.command_timeout = 0ns;
  return o;
}

// A raw protocol client: the test controls every byte and reads what the server sends.
struct RawClient {
  // `names`: the device names it registers (the server's messages from other names are skipped);
  // send() speaks as the first, sendAs() as any.
  explicit RawClient(std::uint16_t port, const std::vector<std::string>& names = {"Phantom0"}) {
    Result<UniqueFd> fd = connectTcp("127.0.0.1", port);
    EXPECT_TRUE(fd) << fd.error().reason;
    conn = std::make_unique<TcpConnection>(std::move(fd).value());
    for (const std::string& n : names) senders[n] = conn->endpoint().addSender(n);
    sender = senders.at(names.front());
    // Registered before the handshake, so the server's messages of these types are delivered.
    for (std::string_view t : {Ping::kTypeName, Pong::kTypeName, TrackerPosQuat::kTypeName, ButtonStates::kTypeName,
                               ButtonChange::kTypeName, ForceError::kTypeName, TextMessage::kTypeName,
                               ForceReport::kTypeName, TrackerVelocity::kTypeName, ForceScp::kTypeName,
                               TrackerToRoom::kTypeName, TrackerUnitToSensor::kTypeName, TrackerWorkspace::kTypeName})
      conn->endpoint().addType(t);
  }
  // Pumps for `d`, collecting messages by type name.
  void pumpFor(std::chrono::milliseconds d) {
    const auto until = std::chrono::steady_clock::now() + d;
    do {  // at least one round, so pumpFor(0ms) still writes and reads
      if (!conn->open()) break;
      pollfd p{conn->fd(), short(POLLIN | (conn->wantsWrite() ? POLLOUT : 0)), 0};
      ::poll(&p, 1, d.count() > 0 ? 2 : 0);
      conn->pump();
      drain();
    } while (std::chrono::steady_clock::now() < until);
    drain();
  }
  void drain() {
    while (std::optional<Event> ev = conn->endpoint().poll()) {
      if (std::holds_alternative<Connected>(*ev)) connected = true;
      if (const auto* m = std::get_if<UserMessage>(&*ev)) {
        const std::string type(m->type_name);
        ++counts[type];
        ++counts_of[std::string(m->sender_name)][type];
        last_payload[type].assign(m->payload.begin(), m->payload.end());
        if (m->type_name == TrackerPosQuat::kTypeName) {
          ++pos_quats;
          if (auto r = TrackerPosQuat::decode(m->payload)) last_pos = last_pos_of[std::string(m->sender_name)] = *r;
        } else if (m->type_name == ButtonStates::kTypeName) {
          ++button_states;
          if (auto r = ButtonStates::decode(m->payload)) last_button_states = r->states;
        } else if (m->type_name == ButtonChange::kTypeName) {
          if (auto r = ButtonChange::decode(m->payload)) changes.push_back(*r);
        } else if (m->type_name == ForceError::kTypeName) {
          if (auto r = ForceError::decode(m->payload)) force_errors.push_back(r->code);
        } else if (m->type_name == TextMessage::kTypeName) {
          if (auto r = TextMessage::decode(m->payload)) texts.push_back(r->text);
        } else if (m->type_name == Pong::kTypeName) {
          ++pongs;
          pos_quats_at_last_pong = pos_quats;
        } else if (m->type_name == ForceReport::kTypeName) {
          if (auto r = ForceReport::decode(m->payload)) last_force = *r;
        }
      }
    }
  }
  bool waitConnected() {
    for (int i = 0; i < 2000 && !connected && conn->open(); ++i) pumpFor(5ms);
    return connected;
  }
  template <class M>
  void send(const M& m) {
    conn->endpoint().sendMessage(sender, m);
  }
  template <class M>
  void sendAs(const std::string& name, const M& m) {
    conn->endpoint().sendMessage(senders.at(name), m);
  }

  std::unique_ptr<TcpConnection> conn;
  std::int32_t sender;
  bool connected = false;
  int pos_quats = 0, button_states = 0, pongs = 0;
  int pos_quats_at_last_pong = 0;  // the reports that came before the newest pong in the stream
  std::vector<std::int32_t> last_button_states;
  TrackerPosQuat last_pos;
  ForceReport last_force;
  std::vector<ButtonChange> changes;
  std::vector<std::int32_t> force_errors;
  std::vector<std::string> texts;
  std::map<std::string, int> counts;  // every message, by type name
  std::map<std::string, std::map<std::string, int>> counts_of;  // by sender name, then type name
  std::map<std::string, TrackerPosQuat> last_pos_of;           // by sender name
  std::map<std::string, std::int32_t> senders;                 // our ids of the names registered
  std::map<std::string, std::vector<std::uint8_t>> last_payload;
};

// Handshake done and pinged (like a stock Remote's first mainloop).
inline void registered(RawClient& c) {
  if (c.waitConnected()) c.send(Ping{});
}

// Pings and reads until the pong: a barrier, since the server answers a link's messages in order.
// Each round of the server's loop reads the servo's newest snapshot before the messages it
// answers, so whatever the servo published before the ping was sent is what the server serves
// once it has answered a second such ping (the first may be answered by a round that read its
// snapshot just before the ping arrived).
inline bool pingedAndAnswered(RawClient& c) {
  const int pongs = c.pongs;
  c.send(Ping{});
  return eventually([&] {
    c.pumpFor(5ms);
    return c.pongs > pongs;
  });
}

// What our client device sends as a Plane message: 100 N/m with the pen 1 mm inside, 0.1 N up
// (below the safety stage's 0.2 N engage threshold, so a missed-tick fault on a loaded machine
// only delays the force, see safety.hpp).
inline dev::DeviceCommand planeCommandAbove(const Eigen::Vector3d& pen) {
  dev::DeviceCommand cmd;
  cmd.forces_enabled = true;
  cmd.num_planes = 1;
  cmd.planes[0].n_world = Eigen::Vector3d::UnitZ();
  cmd.planes[0].d_m = pen.z() + 0.001;
  cmd.planes[0].k_n_per_m = 100.0;
  return cmd;
}

inline ForcePlane ceilingAbove(const Eigen::Vector3d& pen, double depth_m, float kspring) {
  // A floor plane 'depth' above the pen: the pen is that deep inside it, pushed up.
  ForcePlane p;
  p.plane = {0.0f, 0.0f, 1.0f, float(-(pen.z() + depth_m))};
  p.kspring = kspring;
  p.kdamp = 0.0f;
  p.fstat = 0.0f;
  p.fdyn = 0.0f;
  p.n_rec_cycles = 1;
  return p;
}

}  // namespace thx::vrpn::test
