#pragma once
// hapticd's command line: the help text, the parser into one HapticdOptions, and the conversions
// into the option structs the server's parts take (scene policy, publisher, scene switcher, VRPN
// server). hapticd.cpp composes the parts from these; nothing here opens a file or a socket.
//
// Errors are thx::UsageError naming the option, the value given and what was expected; hapticd
// prints them with a pointer to --help and exits 2.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <thx_msgs/protocol.hpp>

#include "device/haptic_device.hpp"
#include "server/flight_dump_limits.hpp"
#include "server/missed_tick_policy.hpp"
#include "server/paper_loop.hpp"
#include "server/port_plan.hpp"
#include "server/prepared_scene.hpp"
#include "server/publisher.hpp"
#include "server/realtime.hpp"
#include "server/scene_switcher.hpp"
#include "server/subscriptions.hpp"
#include "server/vrpn_server.hpp"

namespace thx::srv {

// `hapticd --help`.
const char* hapticdHelp();

struct ListenAddress {
  std::string ip = "127.0.0.1";
  std::uint16_t port = 0;
};

struct HapticdOptions {
  bool help = false;  // -h/--help seen: parsing stopped there (hapticd's main answers it first, thx::runProgram)
  std::string scene;
  std::string scenes_dir;  // empty: the folder of `scene`
  std::string device;      // empty: the scene's
  std::optional<double> duration_s;
  bool lockstep = false;
  std::int64_t spin_ns = 0;  // --spin-us: the device pacer's busy wait before each tick (real time)
  std::string stats_json;
  std::string record;  // --record FILE
  std::string lcm_url = thx_msgs::kDefaultLcmUrl;
  bool no_lcm = false;
  std::string control_port, data_ports;  // --control-port, --data-ports as given ("" = default)
  PortPlan ports;                         // from them, --lcm-url and --max-clients
  int io_priority = 40;                   // --io-priority
  SubscriptionLimits limits;  // --max-clients, --max-rate, --max-bandwidth, --heartbeat-timeout
  bool max_rate_given = false;
  bool crease = true;
  bool passivity = true;
  std::optional<double> stiffness_fraction;
  bool strict_stability = false;
  bool paper_loop = false;                                 // --paper-loop
  MissedTickMode missed_mode = MissedTickMode::RideThrough;  // --missed-policy
  std::optional<double> plane_rate_hz;                     // --plane-rate
  RealtimeOptions rt;
  std::string flight_dir = ".";
  FlightDumpLimits flight_limits;  // --flight-max, --flight-interval
  bool quiet = false;
  bool verbose = false;  // --verbose: the stability budget's findings, explained
  std::string vrpn_listen;  // --vrpn-listen [ADDR:]PORT as given; empty: no VRPN server
  ListenAddress vrpn_address;  // parsed from it
  std::string vrpn_name = "Phantom0";
  bool vrpn_name_given = false;  // --vrpn-name seen (a scene with several devices refuses it)
  std::optional<double> vrpn_report_hz;
  int vrpn_max_clients = 16;
  bool vrpn_plane2 = false;
};

// "[ADDR:]PORT": loopback unless an address is given (the server listens only where told).
std::optional<ListenAddress> parseListenAddress(const std::string& text);

// The arguments after the program name. Throws UsageError.
HapticdOptions parseHapticdOptions(const std::vector<std::string>& args);

// --device vrpn:ADDRESS, else the scene's VRPN address when the scene names a VRPN device and
// --device is not given; "" for a simulated or replayed device.
std::string vrpnAddress(const HapticdOptions& o, const std::string& scene_vrpn_address);

// --stiffness-fraction, --no-crease, --no-passivity, --strict-stability, --paper-loop, --plane-rate.
ScenePolicy scenePolicy(const HapticdOptions& o);
// Where and how client scene switches load (--scenes-dir, or the folder of --scene).
SceneSwitcherOptions sceneSwitcherOptions(const HapticdOptions& o);
// SCHED_FIFO priority of the publisher and receiver threads: --io-priority, 0 under --lockstep.
int ioThreadPriority(const HapticdOptions& o);
// Limits, flight records, data ports and thread priority for a servo at `servo_hz`. What the run
// decides (device and scene names, session, slots, control LCM) is the caller's to set.
PublisherOptions publisherOptions(const HapticdOptions& o, double servo_hz);
// The VRPN endpoint for --vrpn-listen (which must be set) serving `spec` at `servo_hz`.
VrpnServerOptions vrpnServerOptions(const HapticdOptions& o, const dev::DeviceSpec& spec, double servo_hz);

}  // namespace thx::srv
