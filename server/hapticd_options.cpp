#include "server/hapticd_options.hpp"

#include <arpa/inet.h>

#include <cmath>
#include <filesystem>

#include "base/cli_number.hpp"
#include "base/error.hpp"

namespace thx::srv {

namespace {

const char* kHelp = R"(usage: hapticd --scene FILE [options]

The haptic device server: renders the scene's textured surface to the device at 1 kHz and
publishes device and contact state over LCM. A scene that lists several devices (`devices:`)
runs them all under one servo clock, each with its own proxy, safety stage and faults
(docs/hapticd.md, "Several devices in one scene").

  --scene FILE          scene file (docs/scenes.md); e.g. scenes/default.yaml
  --scenes-dir DIR      where a client's scene switch (server_command_t ACTION_LOAD_SCENE, by
                        name) finds NAME.yaml (default: the folder of --scene; docs/hapticd.md)
  --device DEV          sim; vrpn:NAME@HOST[:PORT] or vrpn:NAME@tcp://HOST:PORT for a PHANToM
                        behind a VRPN server; replay:FILE to play a recorded session's pen
                        trajectories back (--record; a scene's device i plays the log's device
                        i) (docs/vrpn.md); default: the scene's device; sim and vrpn: refused
                        for a scene of several devices
  --duration S          run S seconds, then ramp down and stop (default for a simulated device:
                        its script plus 0.5 s; 0 = until SIGINT/SIGTERM)
  --lockstep            simulated or replayed device on a virtual clock: deterministic, runs as
                        fast as it can (and no tick is dropped on the way to --record)
  --record FILE         write every tick's device and contact state to FILE, a standard LCM log,
                        of every device (lcm-logplayer plays it; --device replay:FILE renders it
                        again)
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
  --heartbeat-timeout S suspend a client after S seconds without a heartbeat (default 2)
  --client-grace S      keep a suspended client's streams, port and sequences S seconds more,
                        then forget it (default 10; 0: forget at the timeout). A cable pulled and
                        put back within the grace is served again at once (docs/clients.md §6)
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
  --spin-us US          real time: the servo's device waits out the last US microseconds before
                        each tick in a busy loop instead of asleep (default 0: it sleeps); a kernel
                        that wakes a sleeping thread late (a VM's idle CPU) then makes the tick late
                        only by what exceeds US, for US of CPU every period (clamped below the
                        period; docs/hapticd.md)
  --no-mlock            do not lock memory
  --mlock-eager         fault in and lock every mapped page at start (whole shared libraries);
                        default: lock pages as they are first touched (MCL_ONFAULT)
  --flight-dir DIR      where fault flight records go (default: ., the working folder; one CSV
                        of the last second of ticks per written fault, flight-tick<N>-<fault>.csv;
                        with several devices flight-<device>-tick<N>-<fault>.csv)
  --flight-max N        write at most N flight records per run and device (default 20; 0: none);
                        later faults are counted in the statistics, not written
  --flight-interval S   write a flight record only S seconds of device time or more after the
                        fault of the last one written (default 10; 0: no rate cap)
  --vrpn-listen [ADDR:]PORT  serve the device to VRPN apps as a PHANToM on TCP+UDP PORT at ADDR
                        (default address 127.0.0.1; 0.0.0.0 for every interface; docs/vrpn.md)
  --vrpn-name NAME      the served device's VRPN name (default Phantom0); a scene of several
                        devices serves each under its scene name, and refuses this option
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

[[noreturn]] void usage(const std::string& message) { throw UsageError(message); }

double number(const std::string& option, const std::string& text) { return cli::parseNumber(option, text); }

bool startsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

const char* hapticdHelp() { return kHelp; }

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

HapticdOptions parseHapticdOptions(const std::vector<std::string>& args) {
  HapticdOptions o;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) usage(a + " needs a value");
      return args[++i];
    };
    if (a == "-h" || a == "--help") {
      o.help = true;
      return o;
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
      if (n < 0 || n > 79 || n != std::floor(n)) usage("--io-priority: expected a whole number 0..79 (below the servo's 80), got " + args[i]);
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
    } else if (a == "--client-grace") {
      const double t = number(a, value());
      if (!(t >= 0 && t <= 3600)) usage("--client-grace must be in [0, 3600] s");
      o.limits.client_grace_ns = std::int64_t(std::llround(t * 1e9));
    } else if (a == "--no-crease") {
      o.crease = false;
    } else if (a == "--no-passivity") {
      o.passivity = false;
    } else if (a == "--missed-policy") {
      const std::string p = value();
      if (p == "ride-through") {
        o.missed_mode = MissedTickMode::RideThrough;
      } else if (p == "disengage") {
        o.missed_mode = MissedTickMode::DisengageOnGap;
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
    } else if (a == "--spin-us") {
      const double us = number(a, value());
      if (!(us >= 0 && us <= 10000)) usage("--spin-us: expected microseconds in [0, 10000], got " + args[i]);
      o.spin_ns = std::int64_t(std::llround(us * 1e3));
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
      o.vrpn_name_given = true;
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
  if (!o.device.empty() && o.device != "sim" && !startsWith(o.device, "vrpn:") &&
      !startsWith(o.device, "replay:")) {
    usage("--device: expected 'sim', 'vrpn:NAME@HOST[:PORT]', 'vrpn:NAME@tcp://HOST:PORT' or 'replay:FILE', got '" +
          o.device + "'");
  }
  if (o.device == "replay:") usage("--device replay:FILE needs a file");
  if (startsWith(o.device, "vrpn:") && o.lockstep) usage("--lockstep needs the simulated or a replayed device");
  if (o.plane_rate_hz && !o.paper_loop) usage("--plane-rate applies to --paper-loop only");
  if (!o.vrpn_listen.empty()) {
    const std::optional<ListenAddress> la = parseListenAddress(o.vrpn_listen);
    if (!la) usage("--vrpn-listen: expected [ADDR:]PORT with an IPv4 ADDR and PORT 1..65535, got '" + o.vrpn_listen + "'");
    o.vrpn_address = *la;
  }
  o.ports = planPorts(o.lcm_url, o.limits.max_clients, o.control_port, o.data_ports);  // before a scene is loaded
  return o;
}

std::string vrpnAddress(const HapticdOptions& o, const std::string& scene_vrpn_address) {
  if (startsWith(o.device, "vrpn:")) return o.device.substr(5);
  return o.device.empty() ? scene_vrpn_address : std::string();
}

ScenePolicy scenePolicy(const HapticdOptions& o) {
  std::optional<double> paper_loop_plane_hz;
  if (o.paper_loop) paper_loop_plane_hz = o.plane_rate_hz.value_or(kPaperPlaneRateHz);
  return {.stiffness_fraction = o.stiffness_fraction,
          .crease = o.crease,
          .passivity = o.passivity,
          .strict_stability = o.strict_stability,
          .paper_loop_plane_hz = paper_loop_plane_hz,
          .device_renders_planes = startsWith(o.device, "vrpn:")};
}

SceneSwitcherOptions sceneSwitcherOptions(const HapticdOptions& o) {
  SceneSwitcherOptions sso;
  std::filesystem::path dir = o.scenes_dir.empty() ? std::filesystem::path(o.scene).parent_path() : std::filesystem::path(o.scenes_dir);
  if (dir.empty()) dir = ".";
  sso.scenes_dir = dir.string();
  sso.policy = scenePolicy(o);
  sso.quiet = o.quiet;
  sso.verbose = o.verbose;
  return sso;
}

// Lock-step is not real time, and its servo waits (sleeping) for the publisher to drain the ring:
// a SCHED_FIFO publisher below a spinning SCHED_FIFO servo would never run. Ordinary threads there.
int ioThreadPriority(const HapticdOptions& o) { return o.lockstep ? 0 : o.io_priority; }

PublisherOptions publisherOptions(const HapticdOptions& o, double servo_hz) {
  PublisherOptions po;
  po.limits = o.limits;
  if (!o.max_rate_given) po.limits.max_rate_hz = servo_hz;
  po.log_subscriptions = !o.quiet;
  po.servo_rate_hz = servo_hz;
  po.flight_dir = o.flight_dir;
  po.flight_limits = o.flight_limits;
  if (o.ports.data_first > 0) {
    po.data_bus = o.ports.bus;
    po.data_port_first = o.ports.data_first;
    po.data_port_last = o.ports.data_last;
  }
  po.fifo_priority = ioThreadPriority(o);
  return po;
}

VrpnServerOptions vrpnServerOptions(const HapticdOptions& o, const dev::DeviceSpec& spec, double servo_hz) {
  VrpnServerOptions vso;
  vso.listen_ip = o.vrpn_address.ip;
  vso.port = o.vrpn_address.port;
  vso.device_name = o.vrpn_name;
  vso.max_report_hz = servo_hz;
  vso.report_hz = o.vrpn_report_hz.value_or(servo_hz);
  vso.max_clients = o.vrpn_max_clients;
  vso.render_plane2 = o.vrpn_plane2;
  const double ws = spec.workspace_radius_m;  // a sphere about the device origin
  vso.workspace_min = {-ws, -ws, -ws};
  vso.workspace_max = {ws, ws, ws};
  vso.limits.max_stiffness_n_per_m = spec.max_stiffness_n_per_m;
  vso.limits.peak_force_n = spec.peak_force_n;
  vso.limits.servo_rate_hz = servo_hz;
  return vso;
}

}  // namespace thx::srv
