#pragma once
// VrpnServer: hapticd's device served to VRPN apps as a PHANToM (issue 4; `hapticd --vrpn-listen`).
// One I/O thread; nothing here runs on, or waits for, the servo thread.
//
// Several devices (issue 30): each served device has its own name (Phantom0, Phantom1, ...),
// snapshot slot and effect renderer; one connection carries them all (a stock client opens one
// connection per host and port for every device it names there). Everything below holds per
// device: a client's report rate, button edges and effects are those of the name it addresses,
// and a name's effects are reset when the last client leaves. Messages from a sender that is none
// of the served names are ignored.
//
// What a client sees (docs/vrpn.md §9, one name for three device kinds, default "Phantom0"):
//  - Tracker: `Pos_Quat` and `Velocity` (sensor 0, metres, the device frame) at the client's
//    report rate: report_hz by default, changed per client by `set_update_rate` (clamped to
//    [1, max_report_hz]; a non-finite or non-positive rate is refused with a text message).
//    Stock vrpn_Phantom has one rate for all clients; per-client keeps one app from slowing or
//    flooding another. `Request_Tracker_To_Room` and `Request_Unit_To_Sensor` are answered with
//    identity transforms (`To_Room`, `Unit_To_Sensor` sensor 0: reports are already in the
//    device frame), `Request_Tracker_Workspace` with `Workspace` (the options' box).
//  - Button: `States` on connect and in reply to every ping, `Change` on every edge.
//  - ForceDevice: `Force` (N, what the servo told the device) and `SCP` (the surface contact
//    point) with every tracker report.
//  - Reports (Pos_Quat, Velocity, Force, SCP) and button edges come only from a valid servo
//    snapshot: none before the first valid reading or while the device's readings are invalid.
//  - `Plane` (4 planes, plane_index 0..3), `Force_Field` and `Custom Effect` change the external
//    effects the servo renders (external_effects.hpp), after the clamps of
//    vrpn_effect_commands.hpp. A refused command gets `Force_Error` 0 and a text message naming the
//    field; a clamped one a warning text. Effects are shared by all clients (as on a stock
//    server) and ALL are reset when the last handshaken client disconnects (a socket still in
//    the handshake never commanded anything and keeps nothing alive).
//  - `Plane2` is ignored unless render_plane2 (hapticd --vrpn-plane2): a stock HDAPI PHANToM
//    ignores it (docs/vrpn.md §9: applied only in the GHOST build), and sample clients send
//    placeholder values with every report, which would otherwise add forces. The first ignored
//    Plane2 of a client gets one warning text.
//  - `Reset_Origin` is answered with a warning text (not supported).
//
// Slow readers: while more than report_backlog_bytes wait in a client's output queue, its
// periodic reports are skipped (counted in reports_skipped), so a client that reads slowly (a
// terminal printing every report) gets fewer reports instead of being dropped. Everything else
// (pongs, button messages, replies, texts) is always queued; only if that passes the queue
// bound (1 MiB) is the client dropped. The kernel's send buffer per client is capped too
// (socket_send_buffer_bytes), or megabytes of reports would queue there first, seconds old.
//
// Connections (docs/vrpn.md §1, §10): a TCP listener and a UDP socket on the same port at
// listen_ip (127.0.0.1 unless told otherwise). Direct TCP connects are accepted; a UDP lob
// request is answered by connecting back to the datagram's source address. We never send a
// UDP_DESCRIPTION, so the link is TCP-only. At most max_clients at once: more are closed at
// accept with a log line.
//
// Isolation: every client has its own Endpoint, output queue (bounded as above), handshake
// timeout, and non-blocking socket; a malformed message, a wrong-sized body or an overflowing
// queue drops that client only, with a logged reason. Reports are encoded from the
// servo's DeviceSnapshot slot (a seqlock: the servo never waits for us).
#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "rt/latest_slot.hpp"
#include "server/external_effects.hpp"
#include "server/servo.hpp"
#include "server/vrpn_effect_commands.hpp"

namespace thx::srv {

struct VrpnServerOptions {
  std::string listen_ip = "127.0.0.1";
  std::uint16_t port = 3883;  // 0: an ephemeral port (tests); see VrpnServer::port()
  std::string device_name = "Phantom0";
  double report_hz = 1000.0;      // per client until it sends set_update_rate
  double max_report_hz = 1000.0;  // the servo rate: faster reports would repeat samples
  int max_clients = 16;
  int num_buttons = 2;  // the HDAPI PHANToM's two stylus buttons
  // Reports are skipped for a client with more than this queued: ~200 reports of ~300 bytes
  // (0.2 s at 1 kHz), enough to ride out a hiccup of the reader, small next to the 1 MiB bound.
  std::size_t report_backlog_bytes = 64 * 1024;
  // SO_SNDBUF of each client socket (0: the kernel's autotuning, up to megabytes). Small, so a
  // slow reader's backlog reaches our queue (and the skipping above) within a fraction of a
  // second, and the reports it does read are fresh rather than seconds old.
  int socket_send_buffer_bytes = 64 * 1024;
  bool render_plane2 = false;  // hapticd --vrpn-plane2
  // The Workspace reply, metres, device frame: the box around the workspace sphere
  // (PHANToM Desktop: radius 0.1 m about the device origin).
  std::array<double, 3> workspace_min{-0.1, -0.1, -0.1};
  std::array<double, 3> workspace_max{0.1, 0.1, 0.1};
  EffectLimits limits;
  std::chrono::nanoseconds handshake_timeout{std::chrono::seconds(5)};
  bool log = true;  // one stderr line per connect, drop, refusal
};

struct VrpnServerStatus {
  bool running = false;
  int clients = 0;             // connections open now (handshake included)
  int handshaken_clients = 0;  // of which past the handshake
  std::uint64_t accepted = 0;
  std::uint64_t refused = 0;  // over max_clients
  std::uint64_t lob_requests = 0;
  std::uint64_t bad_lob_requests = 0;
  std::uint64_t drops = 0;  // connections closed by error or the peer
  std::uint64_t commands = 0;
  std::uint64_t refused_commands = 0;
  std::uint64_t reports = 0;          // Pos_Quat messages sent
  std::uint64_t reports_skipped = 0;  // reports not queued for a client that was behind
  std::size_t max_backlog_bytes = 0;  // the largest output queue of any client so far
  std::uint64_t plane2_ignored = 0;   // Plane2 messages ignored (render_plane2 off)
  std::uint64_t tracker_requests = 0;  // To_Room / Unit_To_Sensor / Workspace requests answered
  std::uint64_t effect_resets = 0;
  std::string last_error;
};

// One line for a log: "N clients served, N dropped, N refused, N force commands (N refused), N
// reports skipped for slow readers, N Plane2 ignored".
std::string describe(const VrpnServerStatus& status);

// One device as the server offers it.
struct VrpnServedDevice {
  std::string name;                                       // its sender name
  const rt::LatestSlot<DeviceSnapshot>* snapshots = nullptr;  // its servo's (Servo::publishSnapshots)
  ExternalEffectRenderer* effects = nullptr;              // null: its force commands get Force_Error 3
};

class VrpnServer {
 public:
  // At most this many names (ServoGroup::kMaxDevices).
  static constexpr std::size_t kMaxDevices = 16;
  // One device, named options.device_name. `effects` may be null: force commands are then
  // refused with Force_Error 3.
  VrpnServer(const rt::LatestSlot<DeviceSnapshot>& snapshots, ExternalEffectRenderer* effects,
             VrpnServerOptions options);
  // Several devices (options.device_name unused). Throws thx::Error (Config) for none, more than
  // kMaxDevices, an empty or repeated name, or a device without a snapshot slot.
  VrpnServer(std::vector<VrpnServedDevice> devices, VrpnServerOptions options);
  ~VrpnServer();
  VrpnServer(const VrpnServer&) = delete;
  VrpnServer& operator=(const VrpnServer&) = delete;

  // Binds TCP and UDP and starts the I/O thread. Throws std::runtime_error naming the address
  // and the reason when it cannot bind.
  void start();
  void stop();

  std::uint16_t port() const { return bound_port_; }
  VrpnServerStatus status() const;

 private:
  struct Impl;
  void run();

  std::vector<VrpnServedDevice> devices_;
  VrpnServerOptions options_;
  std::uint16_t bound_port_ = 0;
  std::unique_ptr<Impl> impl_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  mutable std::mutex status_mutex_;
  VrpnServerStatus status_;
};

}  // namespace thx::srv
