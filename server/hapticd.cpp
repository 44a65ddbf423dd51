// hapticd: the haptic device server. Loads a scene, opens the device, runs the 1 kHz servo on a
// real-time thread, publishes device and contact state over LCM, and on SIGINT/SIGTERM (or after
// --duration) ramps the force down and writes its statistics. `hapticd --help` for options.
#include <lcm/lcm-cpp.hpp>
#include <thx_msgs/lcm_open.hpp>
#include <thx_msgs/protocol.hpp>
#include <arpa/inet.h>
#include <malloc.h>
#include <pthread.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "device/replay_device.hpp"
#include "device/sim_phantom.hpp"
#include "device/vrpn/vrpn_client_device.hpp"
#include "scenes/scene_frames.hpp"
#include "scenes/scene_loader.hpp"
#include "base/cli_number.hpp"
#include "scenes/scene_surface.hpp"
#include "server/process_memory.hpp"
#include "server/publisher.hpp"
#include "server/realtime.hpp"
#include "server/receiver.hpp"
#include "server/prepared_scene.hpp"
#include "server/scene_device.hpp"
#include "server/scene_switcher.hpp"
#include "server/servo_rig.hpp"
#include "server/paper_loop.hpp"
#include "server/stability_budget.hpp"
#include "server/session_log.hpp"
#include "server/port_plan.hpp"
#include "server/stats_json.hpp"
#include "server/vrpn_server.hpp"
#include "textures/texture_error.hpp"

namespace {

const char* kHelp = R"(usage: hapticd --scene FILE [options]

The haptic device server: renders the scene's textured surface to the device at 1 kHz and
publishes device and contact state over LCM.

  --scene FILE          scene file (docs/scenes.md); e.g. scenes/default.yaml
  --scenes-dir DIR      where a client's scene switch (server_command_t ACTION_LOAD_SCENE, by
                        name) finds NAME.yaml (default: the folder of --scene; docs/hapticd.md)
  --device DEV          sim; vrpn:NAME@HOST[:PORT] or vrpn:NAME@tcp://HOST:PORT for a PHANToM
                        behind a VRPN server; replay:FILE to play a recorded session's pen
                        trajectory back (--record)
                        (docs/vrpn.md); default: the scene's device
  --duration S          run S seconds, then ramp down and stop (default for a simulated device:
                        its script plus 0.5 s; 0 = until SIGINT/SIGTERM)
  --lockstep            simulated or replayed device on a virtual clock: deterministic, runs as
                        fast as it can (and no tick is dropped on the way to --record)
  --record FILE         write every tick's device and contact state to FILE, a standard LCM log
                        (lcm-logplayer plays it; --device replay:FILE renders it again)
  --stats-json FILE     write statistics (ticks, rate, missed ticks, latencies, memory) as JSON
  --lcm-url URL         LCM transport (default )" THX_DEFAULT_LCM_URL R"()
  --no-lcm              do not publish at all
  --control-port P|off  the udpm port clients send requests, heartbeats, commands and forces to,
                        which only hapticd listens on (default: the --lcm-url port + 1; off: the
                        bus). Named in the hello (docs/clients.md §6)
  --data-ports A-B|off  each client's streams on a udpm port of its own from A..B, recycled when
                        it leaves (default: the --lcm-url port + 2 .. + 1 + --max-clients; off:
                        every stream on the bus). A new client with every port held is refused
  --io-priority P       SCHED_FIFO priority of the publisher and receiver threads, below the
                        servo's 80 (default 40; 0: normal scheduling), so busy clients on the
                        same cores cannot stall every client's streams (docs/clients.md §6)
  --max-clients N       clients served at once (default 32); more are refused (docs/clients.md)
  --max-rate HZ         highest rate granted to one subscription (default: the servo rate)
  --max-bandwidth MB/S  total bandwidth of all subscriptions (default 8 MB/s); more is refused
  --heartbeat-timeout S forget a client after S seconds without a heartbeat (default 2)
  --no-crease           crease handling off (one plane, re-planned every tick; the recovery
                        rule and the passivity controller stay)
  --paper-loop          the source paper's own loop: one plane per graphics frame (--plane-rate),
                        rendered at the servo rate; no crease handling, recovery rule or
                        passivity controller; the safety stage stays (docs/stability.md)
  --plane-rate HZ       planes per second in --paper-loop (default 100, at most the servo rate)
  --no-passivity        passivity controller off (the observer still runs)
  --missed-policy P     what a gap in the servo's ticks does (docs/hapticd.md): ride-through
                        (default: gaps up to 20 ticks, with the pen within Fc/K of where it was
                        (2 mm on the default scene) and at least 80 of the last 100 periods
                        served, keep the force on) or
                        disengage (the old rule: any gap of 3 ticks or more turns the force off
                        and ramps it in again; for comparison)
  --stiffness-fraction F  override the scene's stiffness (fraction of the device maximum)
  --strict-stability    refuse a stiffness above the sampled-wall bound K <= 2(b - |B|)/T
                        (default: warn; the vendor maximum already assumes a damping hand)
  --require-rt          fail if SCHED_FIFO or mlockall cannot be had (default: warn and go on)
  --cpu N               pin the servo thread to CPU N
  --no-mlock            do not lock memory
  --mlock-eager         fault in and lock every mapped page at start (whole shared libraries);
                        default: lock pages as they are first touched (MCL_ONFAULT)
  --flight-dir DIR      where fault flight records go (default: ., the working folder; one CSV
                        of the last second of ticks per written fault, flight-tick<N>-<fault>.csv)
  --flight-max N        write at most N flight records per run (default 20; 0: none); later
                        faults are counted in the statistics, not written
  --flight-interval S   write a flight record only S seconds of device time or more after the
                        fault of the last one written (default 10; 0: no rate cap)
  --vrpn-listen [ADDR:]PORT  serve the device to VRPN apps as a PHANToM on TCP+UDP PORT at ADDR
                        (default address 127.0.0.1; 0.0.0.0 for every interface; docs/vrpn.md)
  --vrpn-name NAME      the served device's VRPN name (default Phantom0)
  --vrpn-report-hz HZ   tracker/force report rate per VRPN client until it sends set_update_rate
                        (default: the servo rate)
  --vrpn-max-clients N  VRPN clients served at once (default 16)
  --vrpn-plane2         render VRPN Plane2 surface effects (texture, buzz, adhesion); default:
                        ignore them, as a stock HDAPI PHANToM does (docs/vrpn.md)
  --quiet               no progress lines
  --verbose             also print the stability-budget check in words (docs/hapticd.md)
  -h, --help            this text

Exit status: 0 clean run, 1 bad input or device failure, 2 bad command line.
)";

std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop.store(true); }

struct Options {
  std::string scene;
  std::string scenes_dir;  // empty: the folder of `scene`
  std::string device;  // empty: the scene's
  std::optional<double> duration_s;
  bool lockstep = false;
  std::string stats_json;
  std::string record;  // --record FILE
  std::string lcm_url = thx_msgs::kDefaultLcmUrl;
  bool no_lcm = false;
  std::string control_port, data_ports;  // --control-port, --data-ports as given ("" = default)
  thx::srv::PortPlan ports;               // from them, --lcm-url and --max-clients
  int io_priority = 40;                   // --io-priority
  thx::srv::SubscriptionLimits limits;  // --max-clients, --max-rate, --max-bandwidth, --heartbeat-timeout
  bool max_rate_given = false;
  bool crease = true;
  bool passivity = true;
  std::optional<double> stiffness_fraction;
  bool strict_stability = false;
  bool paper_loop = false;                                 // --paper-loop
  thx::srv::MissedTickMode missed_mode = thx::srv::MissedTickMode::RideThrough;  // --missed-policy
  std::optional<double> plane_rate_hz;                     // --plane-rate
  thx::srv::RealtimeOptions rt;
  std::string flight_dir = ".";
  thx::srv::FlightDumpLimits flight_limits;  // --flight-max, --flight-interval
  bool quiet = false;
  bool verbose = false;  // --verbose: the stability budget's findings, explained
  std::string vrpn_listen;  // [ADDR:]PORT; empty: no VRPN server
  std::string vrpn_name = "Phantom0";
  std::optional<double> vrpn_report_hz;
  int vrpn_max_clients = 16;
  bool vrpn_plane2 = false;
};

struct ListenAddress {
  std::string ip = "127.0.0.1";
  std::uint16_t port = 0;
};

// "[ADDR:]PORT": loopback unless an address is given (the server listens only where told).
std::optional<ListenAddress> parseListenAddress(const std::string& text) {
  ListenAddress a;
  std::string port = text;
  if (const std::size_t colon = text.rfind(':'); colon != std::string::npos) {
    a.ip = text.substr(0, colon);
    port = text.substr(colon + 1);
    in_addr probe{};
    if (::inet_pton(AF_INET, a.ip.c_str(), &probe) != 1) return std::nullopt;
  }
  if (port.empty() || port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  const long p = std::stol(port);
  if (p < 1 || p > 65535) return std::nullopt;
  a.port = std::uint16_t(p);
  return a;
}

[[noreturn]] void usage(const std::string& message) {
  std::fprintf(stderr, "hapticd: %s (see hapticd --help)\n", message.c_str());
  std::exit(2);
}

double number(const std::string& option, const char* text) {
  try {
    return thx::cli::parseNumber(option, text);
  } catch (const thx::UsageError& e) {
    usage(e.what());
  }
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) usage(a + " needs a value");
      return argv[++i];
    };
    if (a == "-h" || a == "--help") {
      std::fputs(kHelp, stdout);
      std::exit(0);
    } else if (a == "--scene") {
      o.scene = value();
    } else if (a == "--scenes-dir") {
      o.scenes_dir = value();
    } else if (a == "--device") {
      o.device = value();
    } else if (a == "--duration") {
      o.duration_s = number(a, value());
      if (*o.duration_s < 0) usage("--duration must be >= 0");
    } else if (a == "--record") {
      o.record = value();
    } else if (a == "--lockstep") {
      o.lockstep = true;
    } else if (a == "--stats-json") {
      o.stats_json = value();
    } else if (a == "--lcm-url") {
      o.lcm_url = value();
    } else if (a == "--no-lcm") {
      o.no_lcm = true;
    } else if (a == "--control-port") {
      o.control_port = value();
    } else if (a == "--data-ports") {
      o.data_ports = value();
    } else if (a == "--io-priority") {
      const double n = number(a, value());
      if (n < 0 || n > 79 || n != std::floor(n)) usage("--io-priority: expected a whole number 0..79 (below the servo's 80), got " + std::string(argv[i]));
      o.io_priority = int(n);
    } else if (a == "--max-clients") {
      const double n = number(a, value());
      if (n < 1 || n != std::floor(n)) usage("--max-clients must be a whole number >= 1");
      o.limits.max_clients = int(n);
    } else if (a == "--max-rate") {
      o.limits.max_rate_hz = number(a, value());
      o.max_rate_given = true;
      if (o.limits.max_rate_hz <= 0) usage("--max-rate must be > 0");
    } else if (a == "--max-bandwidth") {
      o.limits.max_bandwidth_bytes_per_s = number(a, value()) * 1e6;
      if (o.limits.max_bandwidth_bytes_per_s <= 0) usage("--max-bandwidth must be > 0");
    } else if (a == "--heartbeat-timeout") {
      const double t = number(a, value());
      if (t < 0.05 || t > 3600) usage("--heartbeat-timeout must be in [0.05, 3600] s");
      o.limits.heartbeat_timeout_ns = std::int64_t(std::llround(t * 1e9));
    } else if (a == "--no-crease") {
      o.crease = false;
    } else if (a == "--no-passivity") {
      o.passivity = false;
    } else if (a == "--missed-policy") {
      const std::string p = value();
      if (p == "ride-through") {
        o.missed_mode = thx::srv::MissedTickMode::RideThrough;
      } else if (p == "disengage") {
        o.missed_mode = thx::srv::MissedTickMode::DisengageOnGap;
      } else {
        usage("--missed-policy: expected 'ride-through' or 'disengage', got '" + p + "'");
      }
    } else if (a == "--paper-loop") {
      o.paper_loop = true;
    } else if (a == "--plane-rate") {
      o.plane_rate_hz = number(a, value());
      if (*o.plane_rate_hz <= 0) usage("--plane-rate: expected a rate > 0 Hz");
    } else if (a == "--stiffness-fraction") {
      o.stiffness_fraction = number(a, value());
      if (*o.stiffness_fraction <= 0 || *o.stiffness_fraction > 1) usage("--stiffness-fraction must be in (0, 1]");
    } else if (a == "--strict-stability") {
      o.strict_stability = true;
    } else if (a == "--require-rt") {
      o.rt.require = true;
    } else if (a == "--cpu") {
      o.rt.cpu = int(number(a, value()));
    } else if (a == "--no-mlock") {
      o.rt.lock_memory = false;
    } else if (a == "--mlock-eager") {
      o.rt.lock_on_fault = false;
    } else if (a == "--flight-dir") {
      o.flight_dir = value();
      if (o.flight_dir.empty()) usage("--flight-dir: expected a folder, got ''");
    } else if (a == "--flight-max") {
      const double n = number(a, value());
      if (n < 0 || n > 1e6 || n != std::floor(n)) usage("--flight-max: expected an integer 0..1000000");
      o.flight_limits.max_files = std::uint64_t(n);
    } else if (a == "--flight-interval") {
      o.flight_limits.min_interval_s = number(a, value());
      if (o.flight_limits.min_interval_s < 0 || o.flight_limits.min_interval_s > 86400)
        usage("--flight-interval: expected seconds in [0, 86400]");
    } else if (a == "--vrpn-listen") {
      o.vrpn_listen = value();
    } else if (a == "--vrpn-name") {
      o.vrpn_name = value();
      if (o.vrpn_name.empty() || o.vrpn_name.size() > 95 || o.vrpn_name.find('@') != std::string::npos)
        usage("--vrpn-name: expected 1..95 characters without '@', got '" + o.vrpn_name + "'");
    } else if (a == "--vrpn-report-hz") {
      o.vrpn_report_hz = number(a, value());
      if (*o.vrpn_report_hz <= 0) usage("--vrpn-report-hz must be > 0");
    } else if (a == "--vrpn-max-clients") {
      const double n = number(a, value());
      if (n < 1 || n > 256 || n != std::floor(n)) usage("--vrpn-max-clients: expected an integer 1..256");
      o.vrpn_max_clients = int(n);
    } else if (a == "--vrpn-plane2") {
      o.vrpn_plane2 = true;
    } else if (a == "--quiet") {
      o.quiet = true;
    } else if (a == "--verbose") {
      o.verbose = true;
    } else {
      usage("unknown argument '" + a + "'");
    }
  }
  if (o.scene.empty()) usage("--scene FILE is required");
  if (!o.device.empty() && o.device != "sim" && o.device.rfind("vrpn:", 0) != 0 &&
      o.device.rfind("replay:", 0) != 0) {
    usage("--device: expected 'sim', 'vrpn:NAME@HOST[:PORT]', 'vrpn:NAME@tcp://HOST:PORT' or 'replay:FILE', got '" +
          o.device + "'");
  }
  if (o.device == "replay:") usage("--device replay:FILE needs a file");
  if (o.device.rfind("vrpn:", 0) == 0 && o.lockstep) usage("--lockstep needs the simulated or a replayed device");
  if (o.plane_rate_hz && !o.paper_loop) usage("--plane-rate applies to --paper-loop only");
  if (!o.vrpn_listen.empty() && !parseListenAddress(o.vrpn_listen))
    usage("--vrpn-listen: expected [ADDR:]PORT with an IPv4 ADDR and PORT 1..65535, got '" + o.vrpn_listen + "'");
  try {  // checked here, before a scene is loaded
    o.ports = thx::srv::planPorts(o.lcm_url, o.limits.max_clients, o.control_port, o.data_ports);
  } catch (const thx::UsageError& e) {
    usage(e.what());
  }
  return o;
}

int run(const Options& o) {
  using namespace thx;
  const scene::Scene sc = scene::loadScene(o.scene);
  for (const std::string& w : sc.warnings) std::fprintf(stderr, "hapticd: warning: %s\n", w.c_str());
  std::string vrpn_address;
  if (o.device.rfind("vrpn:", 0) == 0) {
    vrpn_address = o.device.substr(5);
  } else if (o.device.empty() && sc.device.type == scene::DeviceType::Vrpn) {
    vrpn_address = sc.device.address;
  }
  if (!vrpn_address.empty() && o.lockstep) {
    std::fprintf(stderr, "hapticd: %s: --lockstep needs the simulated device, the scene's is VRPN\n", o.scene.c_str());
    return 1;
  }
  const double period_s = 1.0 / sc.rates.servo_hz;
  std::unique_ptr<dev::HapticDevice> device_owner;
  dev::SimPhantom* sim = nullptr;
  dev::ReplayDevice* replay = nullptr;
  if (o.device.rfind("replay:", 0) == 0) {
    dev::ReplayOptions ro;
    ro.period_ns = std::int64_t(std::llround(period_s * 1e9));
    ro.lockstep = o.lockstep;
    auto r_dev = std::make_unique<dev::ReplayDevice>(srv::loadSessionTrajectory(o.device.substr(7)),
                                                     srv::deviceSpecFor(sc), ro);
    replay = r_dev.get();
    if (!o.quiet)
      std::fprintf(stderr, "hapticd: replaying %zu ticks (%.2f s) from %s\n", replay->size(), replay->durationS(),
                   o.device.substr(7).c_str());
    device_owner = std::move(r_dev);
  } else if (vrpn_address.empty()) {
    auto s_dev = std::make_unique<dev::SimPhantom>(srv::simConfigFor(sc, o.lockstep), srv::handScriptFor(sc));
    sim = s_dev.get();
    device_owner = std::move(s_dev);
  } else {
    vrpn::VrpnClientOptions vo;
    vo.period_ns = std::int64_t(std::llround(period_s * 1e9));
    vo.request_rate_hz = sc.rates.servo_hz;  // a fresh pose every tick
    device_owner = std::make_unique<vrpn::VrpnClientDevice>(vrpn_address, srv::deviceSpecFor(sc), vo);
  }
  dev::HapticDevice& device = *device_owner;
  const dev::DeviceSpec& spec = device.spec();

  srv::ScenePolicy policy;
  policy.stiffness_fraction = o.stiffness_fraction;
  policy.crease = o.crease;
  policy.passivity = o.passivity;
  policy.strict_stability = o.strict_stability;
  if (o.paper_loop) policy.paper_loop_plane_hz = o.plane_rate_hz.value_or(srv::kPaperPlaneRateHz);
  std::unique_ptr<srv::PreparedScene> first = srv::prepareScene(sc, o.scene, spec, policy);
  // Above the bound is the normal case with a real device (its vendor maximum counts on the hand's
  // damping): said in words with --verbose only; --strict-stability makes it an error (thrown above).
  if (o.verbose) {
    for (const std::string& line : srv::budgetReport(first->budget))
      std::fprintf(stderr, "hapticd: stability budget: %s\n", line.c_str());
  }
  srv::ServoRigConfig wiring = first->wiring;
  wiring.missed_mode = o.missed_mode;
  const scene::SceneSurface& scene_surface = first->surface;
  const std::size_t texture_bytes = scene_surface.map->bytes();
  const std::string first_scene_name = scene_surface.scene_name;
  const std::uint64_t first_fingerprint = scene_surface.fingerprint;

  srv::ServoRig rig(device, scene_surface.surface, wiring);
  srv::Servo& servo = rig.servo();
  rt::SpscRing<srv::TickRecord>& ring = rig.ring();

  std::unique_ptr<lcm::LCM> lcm, control_lcm;
  const srv::PortPlan& ports = o.ports;
  if (!o.no_lcm) {
    try {
      lcm = thx_msgs::openLcm(o.lcm_url);
    } catch (const thx::Error& e) {  // the haptics do not need the network: warn and go on
      std::fprintf(stderr, "hapticd: warning: %s; the servo runs without publishing\n", e.what());
    }
  }
  if (lcm && ports.control_port > 0) {
    try {
      control_lcm = thx_msgs::openLcm(ports.controlUrl());
    } catch (const thx::Error& e) {  // clients then keep sending to the bus, which still works
      std::fprintf(stderr, "hapticd: warning: %s; clients send to the bus instead\n", e.what());
    }
  }
  srv::PublisherOptions po;
  po.limits = o.limits;
  if (!o.max_rate_given) po.limits.max_rate_hz = sc.rates.servo_hz;
  po.device_name = vrpn_address.empty() ? "sim" : vrpn_address;
  po.scene_name = first_scene_name;
  po.texture_fingerprint = first_fingerprint;
  po.log_subscriptions = !o.quiet;
  po.servo_rate_hz = sc.rates.servo_hz;
  po.flight_dir = o.flight_dir;
  po.flight_limits = o.flight_limits;
  po.simulated_device = sim != nullptr || replay != nullptr;
  std::unique_ptr<srv::SessionRecorder> session;
  if (!o.record.empty()) {
    session = std::make_unique<srv::SessionRecorder>(o.record, po.simulated_device);  // throws with the path
    po.session = session.get();
  }
  po.fault_reset = &servo.faultResetSlot();
  // Owns every scene the servo renders from here on, the first one too; destroyed after the servo
  // thread has ended (declared after the rig, before the publisher that uses it).
  srv::SceneSwitcherOptions sso;
  sso.scenes_dir = o.scenes_dir.empty() ? std::filesystem::path(o.scene).parent_path().string() : o.scenes_dir;
  if (sso.scenes_dir.empty()) sso.scenes_dir = ".";
  sso.policy = policy;
  sso.quiet = o.quiet;
  sso.verbose = o.verbose;
  srv::SceneSwitcher switcher(servo.surfaceSwap(), sc, spec, std::move(first), sso);
  po.scene_loads = &switcher;
  if (ports.data_first > 0) {
    po.data_bus = ports.bus;
    po.data_port_first = ports.data_first;
    po.data_port_last = ports.data_last;
  }
  // Lock-step is not real time, and its servo waits (yielding) for the publisher to drain the ring:
  // a SCHED_FIFO publisher below a spinning SCHED_FIFO servo would never run. Ordinary threads there.
  const int io_priority = o.lockstep ? 0 : o.io_priority;
  po.fifo_priority = io_priority;
  if (control_lcm) {
    po.control_url = ports.controlUrl();
    po.control_lcm = control_lcm.get();
  }
  srv::Publisher publisher(ring, servo, rig.recorder(), lcm.get(), po);
  std::unique_ptr<srv::Receiver> receiver;
  if (lcm) receiver = std::make_unique<srv::Receiver>(*lcm, servo.clientForceSlot(), spec.peak_force_n);
  if (receiver && control_lcm) receiver->listenAlsoOn(*control_lcm);
  if (receiver) receiver->setFifoPriority(io_priority);

  // VRPN apps: effects they command are rendered in the servo; reports come from its snapshots.
  srv::ExternalEffectRenderer external_effects(period_s);
  std::unique_ptr<srv::VrpnServer> vrpn_server;
  if (!o.vrpn_listen.empty()) {
    const ListenAddress la = *parseListenAddress(o.vrpn_listen);
    srv::VrpnServerOptions vso;
    vso.listen_ip = la.ip;
    vso.port = la.port;
    vso.device_name = o.vrpn_name;
    vso.max_report_hz = sc.rates.servo_hz;
    vso.report_hz = o.vrpn_report_hz.value_or(sc.rates.servo_hz);
    vso.max_clients = o.vrpn_max_clients;
    vso.render_plane2 = o.vrpn_plane2;
    const double ws = spec.workspace_radius_m;  // a sphere about the device origin
    vso.workspace_min = {-ws, -ws, -ws};
    vso.workspace_max = {ws, ws, ws};
    vso.limits.max_stiffness_n_per_m = spec.max_stiffness_n_per_m;
    vso.limits.peak_force_n = spec.peak_force_n;
    vso.limits.servo_rate_hz = sc.rates.servo_hz;
    servo.attachExternalEffects(&external_effects);
    vrpn_server = std::make_unique<srv::VrpnServer>(servo.publishSnapshots(), &external_effects, vso);
    vrpn_server->start();  // throws with the address and reason if it cannot bind
    if (!o.quiet)
      std::fprintf(stderr, "hapticd: serving %s to VRPN apps at %s:%u (TCP and UDP)\n", o.vrpn_name.c_str(),
                   la.ip.c_str(), unsigned(vrpn_server->port()));
  }

  // A simulated device runs its script; a real one runs until told to stop.
  // A replay runs to the end of its recording.
  const double duration_s =
      o.duration_s.value_or(sim ? sim->script().duration() + 0.5 : replay ? replay->durationS() : 0.0);
  const std::int64_t stop_tick = duration_s > 0 ? std::int64_t(std::llround(duration_s * sc.rates.servo_hz)) : -1;

  publisher.start();
  if (receiver) receiver->start();
  srv::RealtimeReport rt;
  std::string servo_error;  // written by the servo thread before it sets servo_done
  std::atomic<bool> servo_done{false};
  std::atomic<std::int64_t> ticks_done{0};
  std::int64_t first_deadline = 0, last_deadline = 0;
  const auto wall_start = std::chrono::steady_clock::now();
  std::thread servo_thread([&] {
    try {
      rt = srv::makeThreadRealtime(o.rt);
    } catch (const std::exception& e) {
      servo_error = e.what();
      servo_done.store(true);
      return;
    }
    // Open (and so start the device's clock) only now: locking memory above takes milliseconds,
    // which would otherwise count as missed ticks.
    try {
      device.open();
    } catch (const std::exception& e) {
      servo_error = std::string("cannot open the device: ") + e.what();
      servo_done.store(true);
      return;
    }
    bool shutting_down = false;
    std::int64_t n = 0;
    while (!servo.finished()) {
      // Lock-step is not real time: rather than drop ticks the publisher (and --record) has not
      // taken yet, wait for it. It sleeps, not yields: a yielding SCHED_FIFO thread gives its core
      // only to threads of its own priority or higher, so with two lock-step runs on the two cores
      // neither publisher (an ordinary thread under --lockstep) got a core; they livelocked.
      while (o.lockstep && ring.size() + 2 >= ring.capacity())
        std::this_thread::sleep_for(std::chrono::microseconds(100));
      const srv::TickRecord& r = servo.tick();
      if (n == 0) first_deadline = r.deadline_ns;
      last_deadline = r.deadline_ns;
      ticks_done.store(++n, std::memory_order_relaxed);
      if (!shutting_down && (g_stop.load(std::memory_order_relaxed) || (stop_tick >= 0 && r.tick >= stop_tick))) {
        servo.requestShutdown();
        shutting_down = true;
      }
    }
    servo_done.store(true);
  });
  auto last_report = std::chrono::steady_clock::now();
  while (!servo_done.load()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (!o.quiet && std::chrono::steady_clock::now() - last_report > std::chrono::seconds(2)) {
      last_report = std::chrono::steady_clock::now();
      std::fprintf(stderr, "hapticd: %lld ticks (%.1f s of device time)\n", (long long)ticks_done.load(),
                   double(ticks_done.load()) * period_s);
    }
  }
  servo_thread.join();
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  if (vrpn_server) {
    vrpn_server->stop();
    const srv::VrpnServerStatus vs = vrpn_server->status();
    if (!o.quiet)
      std::fprintf(stderr,
                   "hapticd: vrpn: %llu clients served, %llu dropped, %llu refused, %llu force commands (%llu "
                   "refused), %llu reports skipped for slow readers, %llu Plane2 ignored\n",
                   (unsigned long long)vs.accepted, (unsigned long long)vs.drops, (unsigned long long)vs.refused,
                   (unsigned long long)vs.commands, (unsigned long long)vs.refused_commands,
                   (unsigned long long)vs.reports_skipped, (unsigned long long)vs.plane2_ignored);
  }
  if (receiver) receiver->stop();
  publisher.stop();
  device.close();
  if (session) {
    if (!o.quiet)
      std::fprintf(stderr, "hapticd: recorded %llu ticks to %s\n", (unsigned long long)session->ticks(),
                   session->path().c_str());
    if (ring.dropped() > 0)
      std::fprintf(stderr, "hapticd: warning: %s misses %llu ticks the publisher could not keep up with\n",
                   session->path().c_str(), (unsigned long long)ring.dropped());
  }
  if (!servo_error.empty()) {
    std::fprintf(stderr, "hapticd: %s\n", servo_error.c_str());
    return 1;
  }
  for (const std::string& w : rt.warnings) std::fprintf(stderr, "hapticd: warning: %s\n", w.c_str());

  srv::RunSummary summary;
  summary.scene = o.scene;
  summary.lockstep = o.lockstep;
  summary.ticks = servo.counters().ticks;
  summary.device_time_s = double(last_deadline - first_deadline) * 1e-9 + period_s;
  summary.wall_time_s = wall_s;
  summary.nominal_rate_hz = sc.rates.servo_hz;
  summary.servo = servo.counters();
  summary.missed_policy = servo.missedTickPolicy().counters();
  summary.missed_mode = o.missed_mode;
  summary.safety = rig.safety().counters();
  summary.passivity_active_ticks = rig.passivity().activeTicks();
  summary.passivity_dissipated_j = rig.passivity().dissipatedEnergy();
  summary.realtime = rt;
  summary.memory = srv::readProcessMemory();
  summary.texture_bytes = texture_bytes;  // the first scene's
  summary.publisher = publisher.counters();
  if (receiver) summary.client_forces_accepted = receiver->counters().accepted;
  summary.snapshots_dropped = ring.dropped();
  summary.flight_dir = o.flight_dir;
  summary.last_flight_dump = publisher.lastFlightDump();
  summary.crease = wiring.renderer.crease_handling;
  summary.passivity = wiring.passivity;
  summary.stiffness_n_per_m = wiring.renderer.stiffness_n_per_m;  // the first scene's
  if (!o.stats_json.empty()) srv::writeStatsJson(o.stats_json, summary, servo.computeHistogram(), servo.wakeHistogram());
  srv::printSummary(stdout, summary, servo.computeHistogram(), servo.wakeHistogram());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // First of all: a SIGINT/SIGTERM during start-up (loading a large texture takes a while) must
  // also end in an orderly shutdown with statistics, not in the default action.
  struct sigaction sa {};
  sa.sa_handler = onSignal;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  const Options options = parse(argc, argv);
  // Every thread (ours, LCM's GLib thread) gets a 512 KiB stack instead of glibc's 8 MiB default:
  // under mlockall(MCL_FUTURE) each stack is locked in full, so 8 MiB stacks cost 8 MB of RAM each.
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  pthread_attr_setstacksize(&attr, 512 * 1024);
  pthread_setattr_default_np(&attr);
  pthread_attr_destroy(&attr);
  // One malloc arena: per-thread arenas reserve 64 MiB of address space each, which mlockall
  // counts as locked even though it is never touched.
  mallopt(M_ARENA_MAX, 1);
  try {
    return run(options);
  } catch (const thx::Error& e) {  // scene, texture, hand script, device, files: each names its source
    std::fprintf(stderr, "hapticd: %s\n", e.what());
  }
  return 1;
}
