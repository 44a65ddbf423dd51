// hapticd: the haptic device server. Loads a scene, opens its device (or its devices, under one
// servo clock: server/servo_group.hpp), runs the 1 kHz servo on a real-time thread, publishes
// device and contact state over LCM, and on SIGINT/SIGTERM (or after --duration) ramps the force
// down and writes its statistics. `hapticd --help` for options
// (server/hapticd_options.hpp); the servo's run loop is server/servo_runner.hpp.
#include <lcm/lcm-cpp.hpp>
#include <thx_msgs/lcm_open.hpp>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "base/program_main.hpp"
#include "device/replay_device.hpp"
#include "device/sim_phantom.hpp"
#include "rt/clock.hpp"
#include "scenes/scene_loader.hpp"
#include "server/hapticd_devices.hpp"
#include "server/hapticd_options.hpp"
#include "server/mesh_scene.hpp"
#include "server/multicast_path.hpp"
#include "server/process_memory.hpp"
#include "server/receiver.hpp"
#include "server/scene_device.hpp"
#include "server/servo_group.hpp"
#include "server/servo_rig.hpp"
#include "server/servo_runner.hpp"
#include "server/session_log.hpp"
#include "server/stats_json.hpp"

namespace {

std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop.store(true); }

// What the servo thread runs: one device's servo, or a group of them under one clock.
struct ServoThread {
  std::unique_ptr<thx::rt::MonotonicClock> real_clock;
  std::unique_ptr<thx::rt::VirtualClock> virtual_clock;
  std::unique_ptr<thx::srv::ServoGroup> group;
  std::unique_ptr<thx::srv::ServoRunner> runner;
  const thx::srv::LatencyHistogram* compute = nullptr;  // the whole tick's, every device's
  const thx::srv::LatencyHistogram* wake = nullptr;
};

int run(const thx::srv::HapticdOptions& o) {
  using namespace thx;
  const scene::Scene sc = scene::loadScene(o.scene);
  for (const std::string& w : sc.warnings) std::fprintf(stderr, "hapticd: warning: %s\n", w.c_str());
  const double period_s = 1.0 / sc.rates.servo_hz;
  // A mesh scene's mesh, built once for the scene's renderers and the simulated hands, whose
  // scripts press and stroke on the mesh under their points (device/surface_height.hpp). Both
  // outlive the devices, which are destroyed first.
  const std::shared_ptr<const srv::MeshGeometry> mesh = sc.surface.mesh ? srv::buildMeshGeometry(sc) : nullptr;
  std::unique_ptr<srv::MeshSurfaceHeight> hand_surface;
  if (mesh) hand_surface = srv::handSurfaceFor(sc, *mesh);
  srv::HapticdDevices devices = srv::makeHapticdDevices(o, sc, hand_surface.get());
  const std::size_t count = devices.size();
  const bool several = count > 1;
  for (const srv::SceneDevice& d : devices.devices) {
    if (d.replay && !o.quiet)
      std::fprintf(stderr, "hapticd: replaying %zu ticks (%.2f s) from %s\n", d.replay->size(), d.replay->durationS(),
                   o.device.substr(7).c_str());
  }

  std::unique_ptr<srv::PreparedScene> first = srv::prepareScene(sc, o.scene, devices.specs, srv::scenePolicy(o), mesh);
  // Above the bound is the normal case with a real device (its vendor maximum counts on the hand's
  // damping): said in words with --verbose only; --strict-stability makes it an error (thrown above).
  if (o.verbose) {
    for (std::size_t i = 0; i < count; ++i) {
      for (const std::string& line : srv::budgetReport(first->devices[i].budget))
        std::fprintf(stderr, "hapticd: stability budget%s%s: %s\n", several ? " of " : "",
                     several ? devices.names[i].c_str() : "", line.c_str());
    }
  }
  const std::size_t texture_bytes = first->surface.map->bytes();  // the first scene's
  // One rig per device: its own renderer, passivity, safety, missed-tick policy, flight record, ring.
  std::vector<std::unique_ptr<srv::ServoRig>> rigs;
  for (std::size_t i = 0; i < count; ++i) {
    srv::ServoRigConfig wiring = first->devices[i].wiring;
    wiring.missed_mode = o.missed_mode;
    rigs.push_back(std::make_unique<srv::ServoRig>(*devices.devices[i].device, first->surface.surface, wiring,
                                                   first->devices[i].mesh_renderer.get(),
                                                   first->devices[i].tool.get()));
  }
  srv::ServoRig& rig0 = *rigs[0];

  std::unique_ptr<lcm::LCM> lcm, control_lcm;
  const srv::PortPlan& ports = o.ports;
  if (!o.no_lcm) {
    try {
      lcm = thx_msgs::openLcm(o.lcm_url);
    } catch (const thx::Error& e) {  // the haptics do not need the network: warn and go on
      std::fprintf(stderr, "hapticd: warning: %s; the servo runs without publishing\n", e.what());
    }
  }
  if (lcm && !o.quiet) std::fprintf(stderr, "hapticd: %s\n", srv::describeMulticastPath(o.lcm_url).c_str());
  if (lcm && ports.control_port > 0) {
    try {
      control_lcm = thx_msgs::openLcm(ports.controlUrl());
    } catch (const thx::Error& e) {  // clients then keep sending to the bus, which still works
      std::fprintf(stderr, "hapticd: warning: %s; clients send to the bus instead\n", e.what());
    }
  }
  srv::PublisherOptions po = srv::publisherOptions(o, sc.rates.servo_hz);
  po.device_name = devices.joinedSources();
  po.device_names = devices.joinedNames();
  po.scene_name = first->surface.scene_name;
  po.texture_fingerprint = first->fingerprint;
  po.simulated_device = devices.allSimulated();
  std::unique_ptr<srv::SessionRecorder> session;
  if (!o.record.empty()) {  // every device's ticks, each with its index
    session = std::make_unique<srv::SessionRecorder>(o.record, po.simulated_device);  // throws with the path
    po.session = session.get();
  }
  std::vector<rt::Handoff<const srv::SurfaceSwap>*> handoffs;
  std::vector<srv::PublishedDevice> published;
  std::vector<srv::ForcedDevice> forced;
  for (std::size_t i = 0; i < count; ++i) {
    srv::Servo& servo = rigs[i]->servo();
    po.fault_resets.push_back(&servo.faultResetSlot());
    handoffs.push_back(&servo.surfaceSwap());
    const srv::SceneDevice& d = devices.devices[i];
    published.push_back({&rigs[i]->ring(), &servo, &rigs[i]->recorder(), several ? devices.names[i] : "",
                         d.sim != nullptr || d.replay != nullptr});
    forced.push_back({&servo.clientForceSlot(), devices.specs[i].peak_force_n});
  }
  // Owns every scene the servos render from here on, the first one too; destroyed after the servo
  // thread has ended (declared after the rigs, before the publisher that uses it).
  srv::SceneSwitcher switcher(std::move(handoffs), sc, devices.specs, std::move(first), srv::sceneSwitcherOptions(o));
  po.scene_loads = &switcher;
  if (control_lcm) {
    po.control_url = ports.controlUrl();
    po.control_lcm = control_lcm.get();
  }
  srv::Publisher publisher(std::move(published), lcm.get(), po);
  std::unique_ptr<srv::Receiver> receiver;
  if (lcm) receiver = std::make_unique<srv::Receiver>(*lcm, std::move(forced));
  if (receiver && control_lcm) receiver->listenAlsoOn(*control_lcm);
  if (receiver) receiver->setFifoPriority(srv::ioThreadPriority(o));

  // VRPN apps: effects they command are rendered in each device's servo; reports come from its
  // snapshots. One device is served as --vrpn-name; several under their scene names.
  std::vector<std::unique_ptr<srv::ExternalEffectRenderer>> external_effects;
  std::unique_ptr<srv::VrpnServer> vrpn_server;
  if (!o.vrpn_listen.empty()) {
    std::vector<srv::VrpnServedDevice> served;
    for (std::size_t i = 0; i < count; ++i) {
      external_effects.push_back(std::make_unique<srv::ExternalEffectRenderer>(period_s));
      rigs[i]->servo().attachExternalEffects(external_effects.back().get());
      served.push_back({several ? devices.names[i] : o.vrpn_name, &rigs[i]->servo().publishSnapshots(),
                        external_effects.back().get()});
    }
    vrpn_server = std::make_unique<srv::VrpnServer>(
        std::move(served), srv::vrpnServerOptions(o, srv::mostCautiousSpec(devices.specs), sc.rates.servo_hz));
    vrpn_server->start();  // throws with the address and reason if it cannot bind
    if (!o.quiet)
      std::fprintf(stderr, "hapticd: serving %s to VRPN apps at %s:%u (TCP and UDP)\n",
                   several ? devices.joinedNames().c_str() : o.vrpn_name.c_str(), o.vrpn_address.ip.c_str(),
                   unsigned(vrpn_server->port()));
  }

  // Simulated devices run their scripts; real ones run until told to stop. A replay runs to the
  // end of its recording.
  const double duration_s = o.duration_s.value_or(devices.defaultDurationS());
  const srv::ServoRunnerOptions ro{o.lockstep, srv::stopTickAfter(duration_s, sc.rates.servo_hz), &g_stop};

  publisher.start();
  if (receiver) receiver->start();
  // One device paces itself (its blocking read); several share one clock (server/servo_group.hpp).
  ServoThread st;
  if (several) {
    const auto period_ns = std::int64_t(std::llround(period_s * 1e9));
    rt::Clock* clock = nullptr;
    if (o.lockstep) {
      st.virtual_clock = std::make_unique<rt::VirtualClock>();
      clock = st.virtual_clock.get();
    } else {
      st.real_clock = std::make_unique<rt::MonotonicClock>();
      clock = st.real_clock.get();
    }
    st.group = std::make_unique<srv::ServoGroup>(*clock, period_ns, o.lockstep ? 0 : o.spin_ns);
    for (std::size_t i = 0; i < count; ++i) st.group->add(rigs[i]->servo(), devices.names[i].c_str());
    st.runner = std::make_unique<srv::ServoRunner>(*st.group, ro);
    st.compute = &st.group->computeHistogram();
    st.wake = &st.group->wakeHistogram();
  } else {
    st.runner = std::make_unique<srv::ServoRunner>(rig0.servo(), rig0.ring(), ro);
    st.compute = &rig0.servo().computeHistogram();
    st.wake = &rig0.servo().wakeHistogram();
  }
  srv::ServoRunner& runner = *st.runner;
  const auto wall_start = std::chrono::steady_clock::now();
  runner.start(o.rt);
  auto last_report = std::chrono::steady_clock::now();
  while (!runner.done()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (!o.quiet && std::chrono::steady_clock::now() - last_report > std::chrono::seconds(2)) {
      last_report = std::chrono::steady_clock::now();
      std::fprintf(stderr, "hapticd: %lld ticks (%.1f s of device time)\n", (long long)runner.ticks(),
                   double(runner.ticks()) * period_s);
    }
  }
  runner.join();
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  if (vrpn_server) {
    vrpn_server->stop();
    if (!o.quiet) std::fprintf(stderr, "hapticd: vrpn: %s\n", srv::describe(vrpn_server->status()).c_str());
  }
  if (receiver) receiver->stop();
  publisher.stop();
  for (srv::SceneDevice& d : devices.devices) d.device->close();
  std::uint64_t dropped = 0;
  for (const auto& r : rigs) dropped += r->ring().dropped();
  if (session) {
    if (!o.quiet)
      std::fprintf(stderr, "hapticd: recorded %llu ticks%s to %s\n", (unsigned long long)session->ticks(),
                   several ? (" of " + std::to_string(count) + " devices").c_str() : "", session->path().c_str());
    if (dropped > 0)
      std::fprintf(stderr, "hapticd: warning: %s misses %llu ticks the publisher could not keep up with\n",
                   session->path().c_str(), (unsigned long long)dropped);
  }
  if (!runner.error().empty()) {
    std::fprintf(stderr, "hapticd: %s\n", runner.error().c_str());
    return 1;
  }
  for (const std::string& w : runner.realtime().warnings) std::fprintf(stderr, "hapticd: warning: %s\n", w.c_str());

  srv::RunSummary summary;
  summary.scene = o.scene;
  summary.lockstep = o.lockstep;
  srv::addServoSummary(summary, rig0);
  if (several) {
    for (std::size_t i = 0; i < count; ++i) summary.devices.push_back(srv::deviceSummary(devices.names[i], *rigs[i]));
  }
  summary.device_time_s = runner.deviceTimeS(period_s);
  summary.wall_time_s = wall_s;
  summary.nominal_rate_hz = sc.rates.servo_hz;
  summary.realtime = runner.realtime();
  summary.memory = srv::readProcessMemory();
  summary.texture_bytes = texture_bytes;
  summary.publisher = publisher.counters();
  if (receiver) summary.client_forces_accepted = receiver->counters().accepted;
  summary.snapshots_dropped = dropped;
  summary.flight_dir = o.flight_dir;
  summary.last_flight_dump = publisher.lastFlightDump();
  if (!o.stats_json.empty()) srv::writeStatsJson(o.stats_json, summary, *st.compute, *st.wake);
  srv::printSummary(stdout, summary, *st.compute, *st.wake);
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
  return thx::runProgram("hapticd", thx::srv::hapticdHelp(), argc, argv, [](const std::vector<std::string>& args) {
    const thx::srv::HapticdOptions options = thx::srv::parseHapticdOptions(args);
    thx::srv::prepareProcessForLockedMemory();  // small thread stacks, one malloc arena
    return run(options);  // scene, texture, hand script, device, files: each error names its source
  });
}
