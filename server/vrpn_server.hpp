#pragma once
// VrpnServer: hapticd's device served to VRPN apps as a PHANToM (issue 4; `hapticd --vrpn-listen`).
// One I/O thread; nothing here runs on, or waits for, the servo thread.
//
// What a client sees (reference §9, one name for three device kinds, default "Phantom0"):
//  - Tracker: `Pos_Quat` and `Velocity` (sensor 0, metres, the device frame) at the client's
//    report rate: report_hz by default, changed per client by `set_update_rate` (clamped to
//    [1, max_report_hz]; a non-finite or non-positive rate is refused with a text message).
//    Stock vrpn_Phantom has one rate for all clients; per-client keeps one app from slowing or
//    flooding another.
//  - Button: `States` on connect and in reply to every ping, `Change` on every edge.
//  - ForceDevice: `Force` (N, what the servo told the device) and `SCP` (the surface contact
//    point) with every tracker report.
//  - `Plane` (4 planes, plane_index 0..3), `Plane2`, `Force_Field` and `Custom Effect` change the
//    external effects the servo renders (external_effects.hpp), after the clamps of
//    vrpn_effect_commands.hpp. A refused command gets `Force_Error` 0 and a text message naming the
//    field; a clamped one a warning text. Effects are shared by all clients (as on a stock
//    server) and ALL are reset when the last client disconnects.
//  - `Reset_Origin` is answered with a warning text (not supported).
//
// Connections (reference §1, §10): a TCP listener and a UDP socket on the same port at
// listen_ip (127.0.0.1 unless told otherwise). Direct TCP connects are accepted; a UDP lob
// request is answered by connecting back to the datagram's source address. We never send a
// UDP_DESCRIPTION, so the link is TCP-only. At most max_clients at once: more are closed at
// accept with a log line.
//
// Isolation: every client has its own Endpoint, output queue (1 MiB, then dropped), handshake
// timeout, and non-blocking socket; a malformed message, a wrong-sized body or a client that
// stops reading drops that client only, with a logged reason. Reports are encoded from the
// servo's DeviceSnapshot slot (a seqlock: the servo never waits for us).
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "device/latest_slot.hpp"
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
  EffectLimits limits;
  std::chrono::nanoseconds handshake_timeout{std::chrono::seconds(5)};
  bool log = true;  // one stderr line per connect, drop, refusal
};

struct VrpnServerStatus {
  bool running = false;
  int clients = 0;  // connections open now (handshake included)
  std::uint64_t accepted = 0;
  std::uint64_t refused = 0;  // over max_clients
  std::uint64_t lob_requests = 0;
  std::uint64_t bad_lob_requests = 0;
  std::uint64_t drops = 0;  // connections closed by error or the peer
  std::uint64_t commands = 0;
  std::uint64_t refused_commands = 0;
  std::uint64_t reports = 0;  // Pos_Quat messages sent
  std::uint64_t effect_resets = 0;
  std::string last_error;
};

class VrpnServer {
 public:
  // `effects` may be null: force commands are then refused with Force_Error 3.
  VrpnServer(const dev::LatestSlot<DeviceSnapshot>& snapshots, ExternalEffectRenderer* effects,
             VrpnServerOptions options);
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

  const dev::LatestSlot<DeviceSnapshot>& snapshots_;
  ExternalEffectRenderer* effects_;
  VrpnServerOptions options_;
  std::uint16_t bound_port_ = 0;
  std::unique_ptr<Impl> impl_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  mutable std::mutex status_mutex_;
  VrpnServerStatus status_;
};

}  // namespace thx::srv
