#include "device/vrpn/vrpn_client_device.hpp"

#include <poll.h>
#include <sys/socket.h>
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>

#include "device/vrpn/base_messages.hpp"
#include "device/vrpn/button_messages.hpp"
#include "device/vrpn/report_interval.hpp"
#include "device/vrpn/tcp_connection.hpp"
#include "device/vrpn/tracker_messages.hpp"
#include "device/vrpn/udp_socket.hpp"

namespace thx::vrpn {

namespace {

bool isStop(const ForcePlane& p) {
  return p.plane[0] == 0.0f && p.plane[1] == 0.0f && p.plane[2] == 0.0f && p.plane[3] == 0.0f;
}

void sleepNs(std::int64_t ns) {
  if (ns <= 0) return;
  timespec ts{};
  ts.tv_sec = time_t(ns / 1'000'000'000);
  ts.tv_nsec = long(ns % 1'000'000'000);
  ::nanosleep(&ts, nullptr);
}

// Angular velocity from a rotation `q` (x, y, z, w) over dt seconds.
void omegaFrom(const std::array<double, 4>& q, double dt, double out[3]) {
  out[0] = out[1] = out[2] = 0.0;
  const double s = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
  if (!(dt > 0.0) || !(s > 0.0) || !std::isfinite(s)) return;
  double angle = 2.0 * std::atan2(s, q[3]);
  if (angle > std::numbers::pi) angle -= 2.0 * std::numbers::pi;  // the short way round
  for (int i = 0; i < 3; ++i) out[i] = q[std::size_t(i)] / s * angle / dt;
}

// Mode A (docs/vrpn.md §1): listen on an ephemeral TCP port at the local address that routes to the
// server, send the server "ip port" by UDP, and wait for it to connect back; re-send every
// `resend_ns` (2 s) until it does. step() waits at most poll_ms and returns the accepted socket.
class LobConnector {
 public:
  LobConnector(std::string host, std::uint16_t port, std::int64_t resend_ns, std::function<void()> on_attempt)
      : host_(std::move(host)), port_(port), resend_ns_(resend_ns), on_attempt_(std::move(on_attempt)) {}

  std::optional<UniqueFd> step(std::int64_t now, int poll_ms) {
    if (!listen_) {
      if (now < retry_ns_) {
        sleepNs(std::min<std::int64_t>(retry_ns_ - now, std::int64_t(poll_ms) * 1'000'000));
        return std::nullopt;
      }
      Result<std::string> ip = localAddressTowards(host_, port_);
      Result<UniqueFd> l = ip ? listenTcp(*ip, 0, 1) : Result<UniqueFd>(ip.error());
      if (!l) return fail(now, l.error().reason);
      listen_ = std::move(l).value();
      request_ = encodeLobRequest(*ip, localPort(listen_.get()));
      next_send_ns_ = now;
    }
    if (now >= next_send_ns_) {
      on_attempt_();
      Result<bool> sent = sendDatagram(host_, port_, request_);
      if (!sent) return fail(now, "UDP connection request to " + host_ + ":" + std::to_string(port_) + ": " +
                                      sent.error().reason);
      next_send_ns_ = now + resend_ns_;
    }
    pollfd pfd{listen_.get(), POLLIN, 0};
    ::poll(&pfd, 1, poll_ms);
    Result<UniqueFd> fd = acceptTcp(listen_.get());
    if (!fd) return fail(now, fd.error().reason);
    if (!*fd) return std::nullopt;
    listen_.reset();  // a fresh listener (and request) for the next connection
    error_.clear();
    return std::move(fd).value();
  }
  const std::string& lastError() const { return error_; }

 private:
  std::optional<UniqueFd> fail(std::int64_t now, std::string why) {
    error_ = std::move(why);
    listen_.reset();
    retry_ns_ = now + resend_ns_;
    return std::nullopt;
  }

  std::string host_;
  std::uint16_t port_;
  std::int64_t resend_ns_;
  std::function<void()> on_attempt_;
  UniqueFd listen_;
  std::vector<std::uint8_t> request_;
  std::int64_t next_send_ns_ = 0;
  std::int64_t retry_ns_ = 0;
  std::string error_;
};

}  // namespace

ForcePlane toForcePlane(const dev::PlaneProxy& plane, const dev::DeviceSpec& spec, std::int32_t n_rec_cycles) {
  ForcePlane p;
  p.n_rec_cycles = n_rec_cycles;
  p.plane_index = 0;
  const bool finite = plane.n_world.allFinite() && std::isfinite(plane.d_m) && std::isfinite(plane.k_n_per_m) &&
                      std::isfinite(plane.b_ns_per_m) && std::isfinite(plane.mu_static) &&
                      std::isfinite(plane.mu_dynamic);
  if (!finite) return stopSurface(p);
  p.plane = {float(plane.n_world.x()), float(plane.n_world.y()), float(plane.n_world.z()), float(-plane.d_m)};
  const double kmax = spec.max_stiffness_n_per_m > 0.0 ? spec.max_stiffness_n_per_m : 1.0;
  p.kspring = float(std::clamp(plane.k_n_per_m / kmax, 0.001, 1.0));
  p.kdamp = float(std::clamp(plane.b_ns_per_m / 1000.0, 0.0, 0.005));
  const double fstat = std::clamp(plane.mu_static, 0.0, 1.0);
  p.fstat = float(fstat);
  p.fdyn = float(std::clamp(plane.mu_dynamic, 0.0, fstat));
  return p;
}

VrpnClientDevice::VrpnClientDevice(std::string address, dev::DeviceSpec spec, VrpnClientOptions options)
    : address_text_(std::move(address)),
      spec_(std::move(spec)),
      options_(options),
      pacer_(options_.clock ? *options_.clock : own_clock_, options_.period_ns, options_.spin_ns) {}

VrpnClientDevice::~VrpnClientDevice() { close(); }

void VrpnClientDevice::open() {
  if (io_thread_.joinable()) return;
  Result<DeviceAddress> a = parseDeviceAddress(address_text_);
  if (!a) throw dev::DeviceError("vrpn: " + a.error().reason);
  address_ = *a;
  {
    std::lock_guard lock(status_mutex_);
    status_ = VrpnClientStatus{};
    status_.running = true;
    status_.fresh_for_ns = std::int64_t(options_.staleness.count());
  }
  Command initial{};
  initial.plane = stopSurface(ForcePlane{});
  initial.plane.n_rec_cycles = options_.n_rec_cycles;
  initial.written_ns = monotonic_.nowNs();
  command_slot_.write(initial);
  stop_.store(false);
  pacer_.start();
  io_thread_ = std::thread([this] { ioMain(); });
}

void VrpnClientDevice::close() {
  if (!io_thread_.joinable()) return;
  stop_.store(true);
  io_thread_.join();
  std::lock_guard lock(status_mutex_);
  status_.running = false;
  status_.connected = false;
}

dev::DeviceState VrpnClientDevice::read() { return readTick(pacer_.wait()); }

dev::DeviceState VrpnClientDevice::readTick(const rt::TickTiming& timing) {
  dev::DeviceState s;
  s.timing = timing;
  sample_slot_.readIfNewer(last_sample_, sample_seq_);
  const Sample& m = last_sample_;
  const std::int64_t now = monotonic_.nowNs();
  s.p_world = Eigen::Vector3d(m.pos[0], m.pos[1], m.pos[2]);
  s.v_world = Eigen::Vector3d(m.vel[0], m.vel[1], m.vel[2]);
  s.w_world = Eigen::Vector3d(m.omega[0], m.omega[1], m.omega[2]);
  Eigen::Quaterniond q(m.quat[3], m.quat[0], m.quat[1], m.quat[2]);
  const double qn = q.norm();
  const bool q_ok = std::isfinite(qn) && qn > 0.5 && qn < 2.0;
  if (q_ok) q.normalize();
  s.q_world = q_ok ? q : Eigen::Quaterniond::Identity();
  s.buttons = m.buttons;
  s.valid = m.connected && m.has_pose && q_ok && s.p_world.allFinite() && s.v_world.allFinite() &&
            now - m.pose_ns <= m.fresh_for_ns;
  return s;
}

void VrpnClientDevice::write(const dev::DeviceCommand& command) {
  Command c{};
  if (command.forces_enabled && command.num_planes > 0) {
    c.plane = toForcePlane(command.planes[0], spec_, options_.n_rec_cycles);
  } else {
    c.plane = ForcePlane{};
    c.plane.n_rec_cycles = options_.n_rec_cycles;
    c.plane = stopSurface(c.plane);
  }
  const Eigen::Vector3d& f = command.force_world_n;
  c.field_on = command.forces_enabled && f.allFinite() && f.squaredNorm() > 0.0;
  for (int i = 0; i < 3; ++i) c.force[i] = c.field_on ? float(f[i]) : 0.0f;
  c.written_ns = monotonic_.nowNs();
  command_slot_.write(c);
}

VrpnClientStatus VrpnClientDevice::status() const {
  std::lock_guard lock(status_mutex_);
  return status_;
}

void VrpnClientDevice::ioMain() {
  rt::MonotonicClock clock;
  const std::int64_t reconnect_ns = std::int64_t(options_.reconnect_interval.count());
  const std::int64_t handshake_ns = std::int64_t(options_.handshake_timeout.count());
  const std::int64_t min_send_ns = std::int64_t(options_.min_send_interval.count());
  const std::int64_t timeout_ns = std::int64_t(options_.command_timeout.count());
  const int poll_ms = int(std::max<std::int64_t>(1, std::int64_t(options_.io_poll_interval.count()) / 1'000'000));

  std::unique_ptr<TcpConnection> conn;
  LobConnector lobber(address_.host, address_.port, reconnect_ns, [this] {
    std::lock_guard lock(status_mutex_);
    ++status_.connect_attempts;
  });
  std::int32_t sender = kNoId;
  bool handshaken = false;
  std::int64_t attempt_ns = 0;
  std::int64_t next_attempt_ns = 0;

  const std::int64_t staleness_ns = std::int64_t(options_.staleness.count());
  ReportInterval intervals;
  Sample sample{};
  sample.quat[3] = 1.0;
  sample.fresh_for_ns = staleness_ns;
  auto publish = [&] { sample_slot_.write(sample); };
  publish();

  Command cmd{};
  std::uint32_t cmd_seq = 0;
  command_slot_.readIfNewer(cmd, cmd_seq);
  std::optional<ForcePlane> sent_plane;
  std::optional<ForceField> sent_field;
  std::int64_t plane_sent_ns = 0;
  std::int64_t field_sent_ns = 0;
  bool watchdog_active = false;

  auto setError = [&](std::string text) {
    std::lock_guard lock(status_mutex_);
    status_.last_error = std::move(text);
  };

  // Queues what the newest command asks for, per the send policy in the header.
  auto sendOutputs = [&](std::int64_t now, bool force_stop) {
    command_slot_.readIfNewer(cmd, cmd_seq);
    const bool expired = timeout_ns > 0 && now - cmd.written_ns > timeout_ns;
    // Counted once per episode, and only when the watchdog overrides a live output.
    const bool overriding = expired && (!isStop(cmd.plane) || cmd.field_on);
    if (overriding && !watchdog_active) {
      std::lock_guard lock(status_mutex_);
      ++status_.watchdog_stops;
    }
    watchdog_active = overriding;
    const bool stop = force_stop || expired;
    const ForcePlane want_plane = stop ? stopSurface(cmd.plane) : cmd.plane;
    ForceField want_field;
    if (!stop && cmd.field_on) {
      want_field.force = {cmd.force[0], cmd.force[1], cmd.force[2]};
      want_field.radius = options_.field_radius_m;
    }
    Endpoint& ep = conn->endpoint();
    if ((!sent_plane || *sent_plane != want_plane) && (force_stop || now - plane_sent_ns >= min_send_ns)) {
      if (ep.sendMessage(sender, want_plane)) {
        sent_plane = want_plane;
        plane_sent_ns = now;
        std::lock_guard lock(status_mutex_);
        ++(isStop(want_plane) ? status_.stops_sent : status_.planes_sent);
      }
    }
    if ((!sent_field || *sent_field != want_field) && (force_stop || now - field_sent_ns >= min_send_ns)) {
      if (ep.sendMessage(sender, want_field)) {
        sent_field = want_field;
        field_sent_ns = now;
        std::lock_guard lock(status_mutex_);
        ++status_.fields_sent;
      }
    }
  };

  // Status, and the one-time warning when the server reports slower than staleness allows.
  auto noteReportRate = [&](const ReportInterval& ri) {
    const std::int64_t median = ri.medianNs();
    const double hz = median > 0 ? 1e9 / double(median) : 0.0;
    // Only a full window: the first reports may still come at the old rate, before the server
    // has handled our set_update_rate.
    const bool slow = ri.full() && sample.fresh_for_ns > staleness_ns;
    bool warn = false;
    {
      std::lock_guard lock(status_mutex_);
      status_.observed_report_hz = hz;
      status_.fresh_for_ns = sample.fresh_for_ns;
      warn = slow && !status_.slow_server_warned;
      if (warn) status_.slow_server_warned = true;
    }
    if (warn && options_.log_warnings) {
      char asked[64] = "no rate was asked for";
      if (options_.request_rate_hz > 0.0)
        std::snprintf(asked, sizeof asked, "%g Hz was asked for with set_update_rate", options_.request_rate_hz);
      std::fprintf(stderr,
                   "vrpn: warning: %s sends tracker reports at %.1f Hz (%s). A pose now counts as fresh for "
                   "%.1f ms instead of %.1f ms, so the forces are stepped at %.1f Hz. Raise the server's report "
                   "rate (vrpn.cfg: vrpn_Phantom %s 0 %.1f ...).\n",
                   address_text_.c_str(), hz, asked, double(sample.fresh_for_ns) / 1e6, double(staleness_ns) / 1e6,
                   hz, address_.device.c_str(), options_.request_rate_hz > 0.0 ? options_.request_rate_hz : 1000.0);
    }
  };

  auto handleMessage = [&](const UserMessage& m) {
    if (m.sender != sender) return;
    Endpoint& ep = conn->endpoint();
    const std::string_view t = m.type_name;
    if (t == TrackerPosQuat::kTypeName) {
      Result<TrackerPosQuat> r = TrackerPosQuat::decode(m.payload);
      if (!r) return ep.drop(r.error());
      if (r->sensor != 0) return;
      for (int i = 0; i < 3; ++i) sample.pos[i] = r->pos[std::size_t(i)];
      for (int i = 0; i < 4; ++i) sample.quat[i] = r->quat[std::size_t(i)];
      sample.pose_ns = clock.nowNs();
      sample.has_pose = true;
      intervals.add(sample.pose_ns);
      sample.fresh_for_ns = intervals.freshForNs(staleness_ns);
      publish();
      noteReportRate(intervals);
      std::lock_guard lock(status_mutex_);
      ++status_.pos_reports;
    } else if (t == TrackerVelocity::kTypeName) {
      Result<TrackerVelocity> r = TrackerVelocity::decode(m.payload);
      if (!r) return ep.drop(r.error());
      if (r->sensor != 0) return;
      for (int i = 0; i < 3; ++i) sample.vel[i] = r->vel[std::size_t(i)];
      omegaFrom(r->vel_quat, r->vel_quat_dt, sample.omega);
      publish();
      std::lock_guard lock(status_mutex_);
      ++status_.vel_reports;
    } else if (t == ButtonChange::kTypeName) {
      Result<ButtonChange> r = ButtonChange::decode(m.payload);
      if (!r) return ep.drop(r.error());
      if (r->button >= 0 && r->button < 32) {
        const std::uint32_t bit = 1u << r->button;
        sample.buttons = r->state ? (sample.buttons | bit) : (sample.buttons & ~bit);
        publish();
      }
      std::lock_guard lock(status_mutex_);
      ++status_.button_messages;
    } else if (t == ButtonStates::kTypeName) {
      Result<ButtonStates> r = ButtonStates::decode(m.payload);
      if (!r) return ep.drop(r.error());
      std::uint32_t mask = 0;
      for (std::size_t i = 0; i < r->states.size() && i < 32; ++i)
        if (r->states[i]) mask |= 1u << i;
      sample.buttons = mask;
      publish();
      std::lock_guard lock(status_mutex_);
      ++status_.button_messages;
    } else if (t == ForceReport::kTypeName || t == ForceScp::kTypeName) {
      std::lock_guard lock(status_mutex_);
      ++status_.force_reports;
    } else if (t == ForceError::kTypeName) {
      Result<ForceError> r = ForceError::decode(m.payload);
      if (!r) return ep.drop(r.error());
      std::lock_guard lock(status_mutex_);
      ++status_.force_errors;
      status_.last_force_error = r->code;
    }
  };

  while (!stop_.load(std::memory_order_relaxed)) {
    std::int64_t now = clock.nowNs();
    if (!conn) {
      if (now < next_attempt_ns) {
        sleepNs(std::min<std::int64_t>(next_attempt_ns - now, std::int64_t(poll_ms) * 1'000'000));
        continue;
      }
      std::optional<UniqueFd> fd;
      if (address_.mode == ConnectMode::kTcp) {
        {
          std::lock_guard lock(status_mutex_);
          ++status_.connect_attempts;
        }
        Result<UniqueFd> c = connectTcp(address_.host, address_.port);
        if (!c) {
          setError(c.error().reason);
          next_attempt_ns = now + reconnect_ns;
          continue;
        }
        fd = std::move(c).value();
      } else {
        fd = lobber.step(now, poll_ms);
        if (!fd) {
          if (!lobber.lastError().empty()) setError(lobber.lastError());
          continue;
        }
      }
      conn = std::make_unique<TcpConnection>(std::move(*fd));
      Endpoint& ep = conn->endpoint();
      sender = ep.addSender(address_.device);
      for (std::string_view n : {TrackerPosQuat::kTypeName, TrackerVelocity::kTypeName, ButtonChange::kTypeName,
                                 ButtonStates::kTypeName, Ping::kTypeName, Pong::kTypeName, ForcePlane::kTypeName,
                                 ForceField::kTypeName, ForceReport::kTypeName, ForceScp::kTypeName,
                                 ForceError::kTypeName, TrackerUpdateRate::kTypeName})
        ep.addType(n);
      handshaken = false;
      attempt_ns = now;
      if (sender == kNoId) conn->close(Error{ErrorCode::kBadAddress, "invalid device name"});
    }

    if (conn->open()) {
      pollfd pfd{conn->fd(), short(POLLIN | (conn->wantsWrite() ? POLLOUT : 0)), 0};
      ::poll(&pfd, 1, poll_ms);
      conn->pump();
    }
    while (std::optional<Event> ev = conn->endpoint().poll()) {
      if (std::holds_alternative<Connected>(*ev)) {
        handshaken = true;
        sample.connected = true;
        sample.has_pose = false;
        ++sample.connection;
        intervals.reset();  // a new server (or a restarted one) may report at another rate
        sample.fresh_for_ns = staleness_ns;
        publish();
        sent_plane.reset();
        sent_field = ForceField{};  // a fresh server link starts with no field
        conn->endpoint().sendMessage(sender, Ping{});
        // A stock server keeps its vrpn.cfg rate (often 60 Hz) unless asked (docs/vrpn.md §7, §9).
        const bool asked = options_.request_rate_hz > 0.0 &&
                           conn->endpoint().sendMessage(sender, TrackerUpdateRate{options_.request_rate_hz});
        std::lock_guard lock(status_mutex_);
        ++status_.connects;
        status_.connected = true;
        if (asked) ++status_.rate_requests;
      } else if (const auto* m = std::get_if<UserMessage>(&*ev)) {
        handleMessage(*m);
      }
    }
    now = clock.nowNs();
    if (conn->open() && handshaken) {
      sendOutputs(now, false);
      if (conn->wantsWrite()) conn->pump();
    }
    if (conn->open() && !handshaken && now - attempt_ns > handshake_ns)
      conn->close(Error{ErrorCode::kSocket, "no VRPN handshake within the timeout"});

    if (!conn->open()) {
      while (conn->endpoint().poll()) {
      }
      const std::optional<Error>& reason = conn->closeReason();
      setError(reason ? std::string(toString(reason->code)) + ": " + reason->reason : "connection closed");
      if (handshaken) {
        sample.connected = false;
        sample.has_pose = false;
        ++sample.connection;
        publish();
        std::lock_guard lock(status_mutex_);
        ++status_.drops;
        status_.connected = false;
      }
      conn.reset();
      handshaken = false;
      next_attempt_ns = now + reconnect_ns;
    }
  }

  // Shutting down: stop the surface and the field (best effort, bounded), then close.
  if (conn && conn->open() && handshaken) {
    sendOutputs(clock.nowNs(), true);
    const std::int64_t give_up = clock.nowNs() + 100'000'000;
    while (conn->open() && conn->wantsWrite() && clock.nowNs() < give_up) {
      pollfd pfd{conn->fd(), POLLOUT, 0};
      ::poll(&pfd, 1, 5);
      conn->pump();
      while (conn->endpoint().poll()) {
      }
    }
    // Half-close and read until the server's EOF: closing with unread reports in our receive
    // buffer would send a RST, and the server could lose the stop messages still in its buffer.
    if (conn->open() && !conn->wantsWrite()) {
      ::shutdown(conn->fd(), SHUT_WR);
      while (conn->open() && clock.nowNs() < give_up) {
        pollfd pfd{conn->fd(), POLLIN, 0};
        ::poll(&pfd, 1, 5);
        conn->pump();
        while (conn->endpoint().poll()) {
        }
      }
    }
  }
  if (conn && conn->open()) conn->close(Error{ErrorCode::kPeerClosed, "device closed"});
  sample.connected = false;
  sample.has_pose = false;
  ++sample.connection;
  publish();
  std::lock_guard lock(status_mutex_);
  status_.connected = false;
}

}  // namespace thx::vrpn
