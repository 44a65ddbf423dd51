#include "server/vrpn_server.hpp"

#include <poll.h>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "base/error.hpp"
#include "rt/clock.hpp"
#include "device/vrpn/addressing.hpp"
#include "device/vrpn/base_messages.hpp"
#include "device/vrpn/button_messages.hpp"
#include "device/vrpn/force_messages.hpp"
#include "device/vrpn/tcp_connection.hpp"
#include "device/vrpn/tracker_messages.hpp"
#include "device/vrpn/tracker_transform_messages.hpp"
#include "device/vrpn/udp_socket.hpp"

namespace thx::srv {

using namespace thx::vrpn;

namespace {

// How many kernel-picked ports are tried for a TCP/UDP pair before giving up.
constexpr int kEphemeralPortAttempts = 32;

// What a client has of one served device: its sender id on the connection, its report rate.
struct ClientDevice {
  std::int32_t sender = kNoId;
  double rate_hz = 0.0;
  std::int64_t next_report_ns = 0;
  std::uint32_t buttons_sent = 0;
  bool told_plane2_ignored = false;
};

struct Client {
  std::unique_ptr<TcpConnection> conn;
  std::string peer;  // for log lines
  std::vector<ClientDevice> devices;  // one per served device, in the server's order
  bool connected = false;
  std::int64_t opened_ns = 0;
};

std::string describe(const vrpn::Error& e) { return std::string(toString(e.code)) + ": " + e.reason; }

// A snapshot worth reporting: the servo had a valid reading and everything a report carries is
// finite. Before the first valid reading the snapshot is the default (position 0, identity).
bool reportable(const DeviceSnapshot& d) {
  if (!d.valid) return false;
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(d.p_world[i]) || !std::isfinite(d.v_world[i]) || !std::isfinite(d.f_out[i]) ||
        !std::isfinite(d.scp_world[i]))
      return false;
  for (double q : d.q_world_xyzw)
    if (!std::isfinite(q)) return false;
  return true;
}

}  // namespace

// The server's side of one served device.
struct ServedState {
  ExternalEffects effects;
  bool effects_touched = false;  // something was commanded since the last reset
  DeviceSnapshot snap;
  std::uint32_t snap_seq = 0;
  bool snap_reportable = false;
  std::uint32_t buttons = 0;  // from the newest valid snapshot
};

struct VrpnServer::Impl {
  UniqueFd listen_fd;
  UniqueFd udp_fd;
  std::vector<Client> clients;
  std::vector<ServedState> devices;
};

VrpnServer::VrpnServer(const rt::LatestSlot<DeviceSnapshot>& snapshots, ExternalEffectRenderer* effects,
                       VrpnServerOptions options)
    : VrpnServer(std::vector<VrpnServedDevice>{{options.device_name, &snapshots, effects}}, options) {}

VrpnServer::VrpnServer(std::vector<VrpnServedDevice> devices, VrpnServerOptions options)
    : devices_(std::move(devices)), options_(std::move(options)) {
  const auto refuse = [](const std::string& what) {
    throw thx::Error(thx::Error::Kind::Config, "VRPN server: " + what);
  };
  if (devices_.empty() || devices_.size() > kMaxDevices)
    refuse("serves 1 to " + std::to_string(kMaxDevices) + " devices, asked for " + std::to_string(devices_.size()));
  for (std::size_t i = 0; i < devices_.size(); ++i) {
    if (devices_[i].name.empty()) refuse("device " + std::to_string(i) + " has no name");
    if (!devices_[i].snapshots) refuse("device '" + devices_[i].name + "' has no snapshot slot");
    for (std::size_t j = 0; j < i; ++j)
      if (devices_[j].name == devices_[i].name) refuse("two devices named '" + devices_[i].name + "'");
  }
}

VrpnServer::~VrpnServer() { stop(); }

void VrpnServer::start() {
  if (thread_.joinable()) return;
  auto impl = std::make_unique<Impl>();
  impl->devices.resize(devices_.size());
  const std::string where = options_.listen_ip + ":" + std::to_string(options_.port);
  // The UDP request socket shares the TCP port number (docs/vrpn.md §1). With port 0 the kernel
  // picks a free TCP port whose UDP twin may be taken by another program; a new pick is then
  // tried, so "any free port" never fails by chance while some are free.
  const int attempts = options_.port == 0 ? kEphemeralPortAttempts : 1;
  for (int attempt = 1;; ++attempt) {
    Result<UniqueFd> l = listenTcp(options_.listen_ip, options_.port);
    if (!l) throw thx::Error(thx::Error::Kind::Io, "--vrpn-listen " + where + ": cannot listen on TCP: " + l.error().reason);
    UniqueFd listen_fd = std::move(l).value();
    const std::uint16_t port = localPort(listen_fd.get());
    Result<UniqueFd> u = bindUdp(options_.listen_ip, port);
    if (u) {
      impl->listen_fd = std::move(listen_fd);
      impl->udp_fd = std::move(u).value();
      bound_port_ = port;
      break;
    }
    if (attempt >= attempts)
      throw thx::Error(thx::Error::Kind::Io, "--vrpn-listen " + where + ": cannot bind UDP" +
                                                 (options_.port == 0 ? " on " + std::to_string(attempts) + " ports the kernel picked" : "") +
                                                 ": " + u.error().reason);
  }
  impl_ = std::move(impl);
  {
    std::lock_guard lock(status_mutex_);
    status_ = VrpnServerStatus{};
    status_.running = true;
  }
  stop_.store(false);
  thread_ = std::thread([this] { run(); });
}

void VrpnServer::stop() {
  if (!thread_.joinable()) return;
  stop_.store(true);
  thread_.join();
  std::lock_guard lock(status_mutex_);
  status_.running = false;
  status_.clients = 0;
}

VrpnServerStatus VrpnServer::status() const {
  std::lock_guard lock(status_mutex_);
  return status_;
}

void VrpnServer::run() {
  Impl& s = *impl_;
  rt::MonotonicClock clock;
  const std::int64_t handshake_ns = std::int64_t(options_.handshake_timeout.count());
  const double default_rate = std::clamp(options_.report_hz, 1.0, options_.max_report_hz);

  auto log = [&](const std::string& line) {
    if (options_.log) std::fprintf(stderr, "hapticd: vrpn: %s\n", line.c_str());
  };
  auto bump = [&](auto member, std::uint64_t n = 1) {
    std::lock_guard lock(status_mutex_);
    status_.*member += n;
  };
  auto setError = [&](std::string text) {
    log(text);
    std::lock_guard lock(status_mutex_);
    status_.last_error = std::move(text);
  };

  auto addClient = [&](UniqueFd fd, std::string peer) {
    if (int(s.clients.size()) >= options_.max_clients) {
      bump(&VrpnServerStatus::refused);
      setError("refused " + peer + ": already " + std::to_string(options_.max_clients) +
               " clients (--vrpn-max-clients)");
      return;  // fd closes here
    }
    if (options_.socket_send_buffer_bytes > 0) capSendBuffer(fd.get(), options_.socket_send_buffer_bytes);
    Client c;
    c.conn = std::make_unique<TcpConnection>(std::move(fd));
    Endpoint& ep = c.conn->endpoint();
    for (const VrpnServedDevice& d : devices_) {
      ClientDevice cd;
      cd.sender = ep.addSender(d.name);
      cd.rate_hz = default_rate;
      c.devices.push_back(cd);
    }
    for (std::string_view n :
         {Ping::kTypeName, Pong::kTypeName, TextMessage::kTypeName, TrackerPosQuat::kTypeName,
          TrackerVelocity::kTypeName, TrackerUpdateRate::kTypeName, TrackerResetOrigin::kTypeName,
          TrackerRequestToRoom::kTypeName, TrackerRequestUnitToSensor::kTypeName,
          TrackerRequestWorkspace::kTypeName, TrackerToRoom::kTypeName, TrackerUnitToSensor::kTypeName,
          TrackerWorkspace::kTypeName, ButtonChange::kTypeName, ButtonStates::kTypeName, ForcePlane::kTypeName,
          ForcePlane2::kTypeName, ForceField::kTypeName, ForceCustomEffect::kTypeName, ForceReport::kTypeName,
          ForceScp::kTypeName, ForceError::kTypeName})
      ep.addType(n);
    c.peer = std::move(peer);
    c.opened_ns = clock.nowNs();
    s.clients.push_back(std::move(c));
    bump(&VrpnServerStatus::accepted);
  };

  auto writeEffects = [&](std::size_t k) {
    if (devices_[k].effects) devices_[k].effects->commandSlot().write(s.devices[k].effects);
    s.devices[k].effects_touched = true;
  };

  auto sendText = [&](Client& c, std::size_t k, TextMessage::Severity severity, std::string text) {
    TextMessage t;
    t.severity = severity;
    t.text = std::move(text);
    if (t.text.size() > 1000) t.text.resize(1000);
    c.conn->endpoint().sendMessage(c.devices[k].sender, t);
  };

  auto buttonStates = [&](std::size_t k) {
    ButtonStates b;
    for (int i = 0; i < options_.num_buttons; ++i) b.states.push_back((s.devices[k].buttons >> i) & 1u);
    return b;
  };

  // A force command's verdict: refusals get Force_Error 0 plus the reason; clamps a warning.
  auto answer = [&](Client& c, std::size_t k, const CommandVerdict& v) {
    bump(&VrpnServerStatus::commands);
    if (!v.problem.empty()) {
      bump(&VrpnServerStatus::refused_commands);
      c.conn->endpoint().sendMessage(c.devices[k].sender, ForceError{0});
      sendText(c, k, TextMessage::kError, "hapticd: " + v.problem);
      return;
    }
    if (!v.note.empty()) sendText(c, k, TextMessage::kWarning, "hapticd: " + v.note);
    if (v.applied) writeEffects(k);
  };

  auto handle = [&](Client& c, const UserMessage& m) {
    Endpoint& ep = c.conn->endpoint();
    const std::string_view t = m.type_name;
    std::size_t k = 0;  // the served device the message is addressed to (its sender name)
    while (k < c.devices.size() && c.devices[k].sender != m.sender) ++k;
    if (k == c.devices.size()) return;  // none of ours ("VRPN Control", a client's own sender)
    ClientDevice& cd = c.devices[k];
    ServedState& sd = s.devices[k];
    const std::int32_t sender = cd.sender;
    if (t == Ping::kTypeName) {
      ep.sendMessage(sender, Pong{});
      ep.sendMessage(sender, buttonStates(k));
    } else if (t == TrackerUpdateRate::kTypeName) {
      Result<TrackerUpdateRate> r = TrackerUpdateRate::decode(m.payload);
      if (!r) return ep.drop(r.error());
      if (!std::isfinite(r->hz) || r->hz <= 0.0) {
        sendText(c, k, TextMessage::kError,
                 "hapticd: set_update_rate " + std::to_string(r->hz) + " Hz refused: expected a rate > 0");
        return;
      }
      cd.rate_hz = std::clamp(r->hz, 1.0, options_.max_report_hz);
      if (cd.rate_hz != r->hz)
        sendText(c, k, TextMessage::kWarning,
                 "hapticd: set_update_rate " + std::to_string(r->hz) + " Hz clamped to " +
                     std::to_string(cd.rate_hz) + " Hz");
      cd.next_report_ns = clock.nowNs();
    } else if (t == TrackerResetOrigin::kTypeName) {
      sendText(c, k, TextMessage::kWarning, "hapticd: Reset_Origin is not supported by this device; ignored");
    } else if (t == TrackerRequestToRoom::kTypeName) {
      // Reports are already in the device frame: the tracker-to-room transform is the identity.
      Result<TrackerRequestToRoom> r = TrackerRequestToRoom::decode(m.payload);
      if (!r) return ep.drop(r.error());
      ep.sendMessage(sender, TrackerToRoom{});
      bump(&VrpnServerStatus::tracker_requests);
    } else if (t == TrackerRequestUnitToSensor::kTypeName) {
      // One sensor, the stylus, and the reports are of that sensor itself: the identity.
      Result<TrackerRequestUnitToSensor> r = TrackerRequestUnitToSensor::decode(m.payload);
      if (!r) return ep.drop(r.error());
      ep.sendMessage(sender, TrackerUnitToSensor{});
      bump(&VrpnServerStatus::tracker_requests);
    } else if (t == TrackerRequestWorkspace::kTypeName) {
      Result<TrackerRequestWorkspace> r = TrackerRequestWorkspace::decode(m.payload);
      if (!r) return ep.drop(r.error());
      ep.sendMessage(sender, TrackerWorkspace{options_.workspace_min, options_.workspace_max});
      bump(&VrpnServerStatus::tracker_requests);
    } else if (t == ForcePlane::kTypeName || t == ForcePlane2::kTypeName || t == ForceField::kTypeName ||
               t == ForceCustomEffect::kTypeName) {
      if (!devices_[k].effects) {
        ep.sendMessage(sender, ForceError{3});
        sendText(c, k, TextMessage::kError, "hapticd: this server renders no force effects");
        return;
      }
      if (t == ForcePlane::kTypeName) {
        Result<ForcePlane> r = ForcePlane::decode(m.payload);
        if (!r) return ep.drop(r.error());
        answer(c, k, applyPlane(sd.effects, *r, options_.limits));
      } else if (t == ForcePlane2::kTypeName) {
        Result<ForcePlane2> r = ForcePlane2::decode(m.payload);
        if (!r) return ep.drop(r.error());
        if (!options_.render_plane2) {
          // As a stock HDAPI PHANToM (docs/vrpn.md §9): sample clients send placeholder Plane2
          // values with every report, which must not add forces the app never meant.
          bump(&VrpnServerStatus::plane2_ignored);
          if (!cd.told_plane2_ignored)
            sendText(c, k, TextMessage::kWarning,
                     "hapticd: Plane2 (surface texture, buzz, adhesion) is ignored, as by a stock HDAPI "
                     "PHANToM; start hapticd with --vrpn-plane2 to render it");
          cd.told_plane2_ignored = true;
          return;
        }
        answer(c, k, applyPlane2(sd.effects, *r, options_.limits));
      } else if (t == ForceField::kTypeName) {
        Result<ForceField> r = ForceField::decode(m.payload);
        if (!r) return ep.drop(r.error());
        answer(c, k, applyField(sd.effects, *r, options_.limits));
      } else {
        Result<ForceCustomEffect> r = ForceCustomEffect::decode(m.payload);
        if (!r) return ep.drop(r.error());
        answer(c, k, applyCustomEffect(sd.effects, *r, options_.limits));
      }
    }
    // Our own report types coming back from a client are ignored, like a stock server does.
  };

  auto sendReports = [&](Client& c, std::size_t k) {
    Endpoint& ep = c.conn->endpoint();
    const ClientDevice& cd = c.devices[k];
    const DeviceSnapshot& d = s.devices[k].snap;
    TrackerPosQuat pq;
    TrackerVelocity vel;
    ForceReport force;
    ForceScp scp;
    for (int i = 0; i < 3; ++i) {
      pq.pos[std::size_t(i)] = d.p_world[i];
      vel.vel[std::size_t(i)] = d.v_world[i];
      force.force[std::size_t(i)] = d.f_out[i];
      scp.pos[std::size_t(i)] = d.scp_world[i];
    }
    for (int i = 0; i < 4; ++i) pq.quat[std::size_t(i)] = d.q_world_xyzw[i];
    vel.vel_quat_dt = 1.0 / cd.rate_hz;
    ep.sendMessage(cd.sender, pq);
    ep.sendMessage(cd.sender, vel);
    ep.sendMessage(cd.sender, force);
    ep.sendMessage(cd.sender, scp);
    bump(&VrpnServerStatus::reports);
  };

  auto sendButtonEdges = [&](Client& c, std::size_t k) {
    ClientDevice& cd = c.devices[k];
    const std::uint32_t now_buttons = s.devices[k].buttons;
    for (int i = 0; i < options_.num_buttons && i < 32; ++i) {
      const std::uint32_t bit = 1u << i;
      if ((now_buttons ^ cd.buttons_sent) & bit)
        c.conn->endpoint().sendMessage(cd.sender, ButtonChange{i, (now_buttons & bit) ? 1 : 0});
    }
    cd.buttons_sent = now_buttons;
  };

  std::vector<pollfd> fds;
  while (!stop_.load(std::memory_order_relaxed)) {
    // Wait for input, or for the next report that is due.
    std::int64_t now = clock.nowNs();
    std::int64_t wait_ns = 10'000'000;
    for (const Client& c : s.clients)
      if (c.connected)
        for (const ClientDevice& cd : c.devices)
          wait_ns = std::min(wait_ns, std::max<std::int64_t>(0, cd.next_report_ns - now));
    fds.clear();
    fds.push_back({s.listen_fd.get(), POLLIN, 0});
    fds.push_back({s.udp_fd.get(), POLLIN, 0});
    for (const Client& c : s.clients)
      fds.push_back({c.conn->fd(), short(POLLIN | (c.conn->wantsWrite() ? POLLOUT : 0)), 0});
    timespec ts{time_t(wait_ns / 1'000'000'000), long(wait_ns % 1'000'000'000)};
    ::ppoll(fds.data(), nfds_t(fds.size()), &ts, nullptr);

    if (fds[0].revents & POLLIN) {
      for (;;) {
        Result<UniqueFd> fd = acceptTcp(s.listen_fd.get());
        if (!fd) {
          setError("accept failed: " + fd.error().reason);
          break;
        }
        if (!*fd) break;
        const std::string peer = peerName(fd->get());
        addClient(std::move(fd).value(), peer + " (TCP)");
      }
    }
    if (fds[1].revents & POLLIN) {
      // Answer each distinct request once per round: a waiting client re-sends every 2 s.
      std::vector<std::pair<std::string, std::uint16_t>> answered;
      while (std::optional<Datagram> d = receiveDatagram(s.udp_fd.get())) {
        bump(&VrpnServerStatus::lob_requests);
        Result<LobRequest> req = d->oversized ? Result<LobRequest>(vrpn::Error{ErrorCode::kBadLobRequest,
                                                                         "datagram longer than 256 bytes"})
                                              : parseLobRequest(d->bytes);
        if (!req) {
          bump(&VrpnServerStatus::bad_lob_requests);
          setError("ignored a UDP connection request from " + d->source_ip + ": " + req.error().reason);
          continue;
        }
        const std::pair<std::string, std::uint16_t> key{d->source_ip, req->port};
        if (std::find(answered.begin(), answered.end(), key) != answered.end()) continue;
        answered.push_back(key);
        Result<UniqueFd> fd = connectTcp(d->source_ip, req->port);
        if (!fd) {
          setError("cannot connect back to " + d->source_ip + ":" + std::to_string(req->port) + ": " +
                   fd.error().reason);
          continue;
        }
        addClient(std::move(fd).value(), d->source_ip + ":" + std::to_string(req->port) + " (UDP request)");
      }
    }

    for (std::size_t k = 0; k < devices_.size(); ++k) {
      ServedState& sd = s.devices[k];
      if (devices_[k].snapshots->readIfNewer(sd.snap, sd.snap_seq)) {
        sd.snap_reportable = reportable(sd.snap);
        if (sd.snap_reportable) sd.buttons = sd.snap.buttons;  // an invalid reading's buttons mean nothing
      }
    }
    now = clock.nowNs();
    std::size_t backlog = 0;
    for (Client& c : s.clients) {
      c.conn->pump();
      while (std::optional<Event> ev = c.conn->endpoint().poll()) {
        if (const auto* con = std::get_if<Connected>(&*ev)) {
          c.connected = true;
          for (std::size_t k = 0; k < c.devices.size(); ++k) {
            c.devices[k].next_report_ns = now;
            c.devices[k].buttons_sent = s.devices[k].buttons;
            c.conn->endpoint().sendMessage(c.devices[k].sender, buttonStates(k));
          }
          log("client connected: " + c.peer + (con->peer.minor_differs ? " (different VRPN minor version)" : ""));
        } else if (const auto* m = std::get_if<UserMessage>(&*ev)) {
          handle(c, *m);
        }
      }
      if (!c.conn->open()) continue;
      if (!c.connected && now - c.opened_ns > handshake_ns) {
        c.conn->close(vrpn::Error{ErrorCode::kSocket, "no VRPN handshake within the timeout"});
        continue;
      }
      if (c.connected) {
        for (std::size_t k = 0; k < c.devices.size(); ++k) {
          ClientDevice& cd = c.devices[k];
          sendButtonEdges(c, k);
          if (now < cd.next_report_ns) continue;
          // Nothing to report without a valid reading. A client that is behind skips reports
          // (the next one carries the newer state anyway) rather than growing its queue to the
          // bound and being dropped.
          if (s.devices[k].snap_reportable) {
            if (c.conn->endpoint().pendingOutput().size() > options_.report_backlog_bytes)
              bump(&VrpnServerStatus::reports_skipped);
            else
              sendReports(c, k);
          }
          const std::int64_t period = std::int64_t(1e9 / cd.rate_hz);
          cd.next_report_ns += period;
          if (cd.next_report_ns < now) cd.next_report_ns = now + period;  // fell behind: no burst
        }
      }
      if (c.conn->wantsWrite()) c.conn->pump();
      backlog = std::max(backlog, c.conn->endpoint().pendingOutput().size());
    }

    // Forget closed clients; the last one out resets every effect (docs/vrpn.md §9).
    for (Client& c : s.clients) {
      if (c.conn->open()) continue;
      while (c.conn->endpoint().poll()) {
      }
      const std::optional<vrpn::Error>& why = c.conn->closeReason();
      const bool clean = why && why->code == ErrorCode::kPeerClosed;
      if (!clean) bump(&VrpnServerStatus::drops);
      log("client " + c.peer + (clean ? " disconnected" : " dropped: " + (why ? describe(*why) : "closed")));
      if (!clean && why) {
        std::lock_guard lock(status_mutex_);
        status_.last_error = c.peer + ": " + describe(*why);
      }
    }
    std::erase_if(s.clients, [](const Client& c) { return !c.conn->open(); });
    // Only a handshaken client can command effects, so only those keep them alive: a socket
    // stuck in the handshake (or a port scanner) must not hold a plane after the app left.
    const int handshaken =
        int(std::count_if(s.clients.begin(), s.clients.end(), [](const Client& c) { return c.connected; }));
    for (std::size_t k = 0; k < devices_.size(); ++k) {
      if (handshaken > 0 || !s.devices[k].effects_touched) continue;
      resetEffects(s.devices[k].effects);
      writeEffects(k);
      s.devices[k].effects_touched = false;
      bump(&VrpnServerStatus::effect_resets);
      log("last client gone: all force effects of " + devices_[k].name + " reset");
    }
    std::lock_guard lock(status_mutex_);
    status_.clients = int(s.clients.size());
    status_.handshaken_clients = handshaken;
    status_.max_backlog_bytes = std::max(status_.max_backlog_bytes, backlog);
  }

  // Shutting down: tell the servo nothing is commanded any more.
  for (std::size_t k = 0; k < devices_.size(); ++k) {
    if (!s.devices[k].effects_touched) continue;
    resetEffects(s.devices[k].effects);
    if (devices_[k].effects) devices_[k].effects->commandSlot().write(s.devices[k].effects);
  }
  for (Client& c : s.clients) c.conn->close(vrpn::Error{ErrorCode::kPeerClosed, "server shutting down"});
  s.clients.clear();
}

std::string describe(const VrpnServerStatus& s) {
  char line[320];
  std::snprintf(line, sizeof line,
                "%llu clients served, %llu dropped, %llu refused, %llu force commands (%llu refused), %llu reports "
                "skipped for slow readers, %llu Plane2 ignored",
                (unsigned long long)s.accepted, (unsigned long long)s.drops, (unsigned long long)s.refused,
                (unsigned long long)s.commands, (unsigned long long)s.refused_commands,
                (unsigned long long)s.reports_skipped, (unsigned long long)s.plane2_ignored);
  return line;
}

}  // namespace thx::srv
