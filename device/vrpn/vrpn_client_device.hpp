#pragma once
// VrpnClientDevice: a PHANToM served by a stock VRPN server (vrpn_Phantom), as a HapticDevice in
// OutputMode::Planes (issue 4). Address "Phantom0@tcp://host:port" (direct TCP, docs/vrpn.md
// §1 mode B) or "Phantom0@host[:port]" (mode A: a UDP request, then the server connects back to
// an ephemeral TCP listener of ours; the request is re-sent every reconnect_interval until it
// does).
//
// Threads:
//  - A background I/O thread owns the TcpConnection + Endpoint. It connects, retries every
//    reconnect_interval (2 s, docs/vrpn.md §1/§10) after a failure or a drop, pings on each connect
//    (so the server sends Button States, §6), asks for request_rate_hz reports with
//    `vrpn_Tracker set_update_rate` on each connect (a stock vrpn_Phantom otherwise keeps its
//    vrpn.cfg rate, often 60 Hz, §9), and decodes `vrpn_Tracker Pos_Quat` / `Velocity`
//    (sensor 0) and `vrpn_Button Change` / `States` from our sender name into a latest-value slot.
//    ForceDevice Force/SCP/Force_Error are counted for diagnostics. A message that fails to
//    decode drops the link (docs/vrpn.md §4), which then reconnects.
//  - The servo thread calls read()/write(): neither allocates nor locks; read() sleeps on the
//    Pacer (the servo period on the given Clock) and then returns the newest state.
//
// read(): valid = false while disconnected, before the first Pos_Quat of a connection, or when
// the newest Pos_Quat is older than max(`staleness`, 1.5 x the server's observed report
// interval) (report_interval.hpp; staleness default 5 ms; measured on CLOCK_MONOTONIC at
// arrival, whatever clock paces read()). A server that keeps reporting slower than that allows
// (it ignored set_update_rate) stays usable, with forces stepped at its rate; the I/O thread
// then prints one warning on stderr naming the observed rate (log_warnings). Buttons: bit i =
// button i (first 32).
//
// write() stores the command in a slot; the I/O thread turns it into wire messages:
//  - planes[0] -> `vrpn_ForceDevice Plane` (toForcePlane below); num_planes == 0 or
//    forces_enabled == false -> stop surface (plane (0,0,0,0), docs/vrpn.md §9). Only planes[0] is
//    sent: the stock Remote always sends plane_index 0 (and vrpn_Phantom does not bounds-check it).
//  - force_world_n != 0 with forces enabled -> `Force_Field` with that constant force, J = 0,
//    radius field_radius (default 100 m, as the stock Remote's constraints); when it returns to
//    zero (or forces are disabled) one all-zero field ("stop", §9).
//  - Send policy: a message is sent only when its encoded value differs from the last one sent on
//    this connection, and at most once per min_send_interval (default 1 ms, i.e. <= 1 kHz per
//    message kind); a change that arrives inside the interval is coalesced (the newest value is
//    sent when the interval ends). On each (re)connect the current surface (or a stop) is sent.
//  - Watchdog: if write() has not been called for command_timeout (default 10 ms; 0 disables),
//    the I/O thread sends stop surface + stop field, as the contract's "output zero".
//
// open()/close() run outside the servo loop; open() throws DeviceError for a bad address and
// starts the I/O thread (it does not wait for the connection). status() is for diagnostics (takes
// a mutex, not for the servo thread).
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "rt/clock.hpp"
#include "device/haptic_device.hpp"
#include "rt/pacer.hpp"
#include "device/vrpn/addressing.hpp"
#include "device/vrpn/force_messages.hpp"
#include "rt/latest_slot.hpp"

namespace thx::vrpn {

struct VrpnClientOptions {
  std::int64_t period_ns = 1'000'000;  // servo period read() paces at
  std::int64_t spin_ns = 0;            // the last spin_ns of each period busy-waited (rt::Pacer)
  rt::Clock* clock = nullptr;         // paces read(); nullptr = an internal MonotonicClock
  std::chrono::nanoseconds staleness{std::chrono::milliseconds(5)};
  std::chrono::nanoseconds reconnect_interval{std::chrono::seconds(2)};
  std::chrono::nanoseconds handshake_timeout{std::chrono::seconds(5)};
  std::chrono::nanoseconds min_send_interval{std::chrono::milliseconds(1)};
  std::chrono::nanoseconds command_timeout{std::chrono::milliseconds(10)};  // 0: no watchdog
  std::chrono::nanoseconds io_poll_interval{std::chrono::milliseconds(1)};  // I/O thread wake-up
  std::int32_t n_rec_cycles = 1;  // sent as is; stock vrpn_Phantom ignores it (docs/vrpn.md §9)
  float field_radius_m = 100.0f;
  // Report rate asked for with set_update_rate on every connect: the servo rate, so each tick
  // sees a fresh pose. <= 0: never ask (the server's own rate).
  double request_rate_hz = 1000.0;
  bool log_warnings = true;  // the slow-server warning on stderr
};

struct VrpnClientStatus {
  bool running = false;    // the I/O thread is running
  bool connected = false;  // handshake done, link up
  std::uint64_t connect_attempts = 0;
  std::uint64_t connects = 0;  // completed handshakes
  std::uint64_t drops = 0;     // links lost after the handshake
  std::uint64_t pos_reports = 0;
  std::uint64_t vel_reports = 0;
  std::uint64_t button_messages = 0;
  std::uint64_t force_reports = 0;  // ForceDevice Force / SCP
  std::uint64_t force_errors = 0;   // ForceDevice Force_Error
  std::int32_t last_force_error = -1;
  std::uint64_t planes_sent = 0;
  std::uint64_t stops_sent = 0;
  std::uint64_t fields_sent = 0;
  std::uint64_t watchdog_stops = 0;
  std::uint64_t rate_requests = 0;    // set_update_rate messages sent
  double observed_report_hz = 0.0;    // from the median Pos_Quat interval; 0 until measured
  std::int64_t fresh_for_ns = 0;      // how old a pose may be and still be valid, now
  bool slow_server_warned = false;    // the one-time warning was given
  std::string last_error;  // empty if none so far
};

// One PlaneProxy (n.x = d, n outward, SI units) as a vrpn_Phantom Plane message:
//  - plane (a,b,c,d) = (n, -d): free space where a x + b y + c z + d > 0 (docs/vrpn.md §9);
//  - kspring = k / spec.max_stiffness_n_per_m, clamped to [0.001, 1] like the server;
//  - kdamp = b / 1000 (N·s/mm, GHOST's unit, which the server clamps to [0, 0.005]: 0.005 N·s/mm
//    is the 5 N·s/m PHANToM Desktop maximum) [assumption: docs/vrpn.md §9 gives only the range];
//  - fstat = mu_static clamped to [0, 1], fdyn = mu_dynamic clamped to [0, fstat];
//  - plane_index 0, n_rec_cycles as given.
// A non-finite plane becomes a stop surface.
ForcePlane toForcePlane(const dev::PlaneProxy& plane, const dev::DeviceSpec& spec, std::int32_t n_rec_cycles);

class VrpnClientDevice final : public dev::HapticDevice {
 public:
  // `address`: "Name@tcp://host:port" (or tcp:host:port), or "Name@host[:port]". Parsed in open().
  VrpnClientDevice(std::string address, dev::DeviceSpec spec, VrpnClientOptions options = {});
  ~VrpnClientDevice() override;
  VrpnClientDevice(const VrpnClientDevice&) = delete;
  VrpnClientDevice& operator=(const VrpnClientDevice&) = delete;

  const dev::DeviceSpec& spec() const override { return spec_; }
  dev::OutputMode outputMode() const override { return dev::OutputMode::Planes; }
  void open() override;
  void close() override;
  dev::DeviceState read() override;
  // The newest state at a tick a group's clock paced (server/servo_group.hpp); does not wait.
  bool sharesClock() const override { return true; }
  dev::DeviceState readTick(const rt::TickTiming& timing) override;
  void write(const dev::DeviceCommand& command) override;

  VrpnClientStatus status() const;
  const DeviceAddress& address() const { return address_; }

  // Plain-data snapshots crossing threads (public for the .cpp's helpers; not an API).
  struct Sample {
    double pos[3];
    double quat[4];  // x, y, z, w
    double vel[3];
    double omega[3];
    std::uint32_t buttons;
    std::uint32_t connection;  // increments on every connect / drop
    std::int64_t pose_ns;      // CLOCK_MONOTONIC arrival time of the newest Pos_Quat
    std::int64_t fresh_for_ns;  // the pose is valid until pose_ns + this
    bool connected;
    bool has_pose;  // a Pos_Quat arrived on this connection
  };
  struct Command {
    ForcePlane plane;  // already converted; plane (0,0,0,0) = stop
    float force[3];
    std::int64_t written_ns;  // CLOCK_MONOTONIC
    bool field_on;
  };

 private:
  void ioMain();

  std::string address_text_;
  DeviceAddress address_;
  dev::DeviceSpec spec_;
  VrpnClientOptions options_;

  rt::MonotonicClock own_clock_;
  rt::MonotonicClock monotonic_;  // staleness and command stamps
  rt::Pacer pacer_;

  rt::LatestSlot<Sample> sample_slot_;
  rt::LatestSlot<Command> command_slot_;
  Sample last_sample_{};
  std::uint32_t sample_seq_ = 0;

  std::atomic<bool> stop_{false};
  std::thread io_thread_;
  mutable std::mutex status_mutex_;
  VrpnClientStatus status_;
};

}  // namespace thx::vrpn
