// hapticd: the haptic device server. Loads a scene, opens the device, runs the 1 kHz servo on a
// real-time thread, publishes device and contact state over LCM, and on SIGINT/SIGTERM (or after
// --duration) ramps the force down and writes its statistics. `hapticd --help` for options
// (server/hapticd_options.hpp); the servo's run loop is server/servo_runner.hpp.
#include <lcm/lcm-cpp.hpp>
#include <thx_msgs/lcm_open.hpp>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "base/program_main.hpp"
#include "device/replay_device.hpp"
#include "device/sim_phantom.hpp"
#include "scenes/scene_loader.hpp"
#include "server/hapticd_options.hpp"
#include "server/mesh_scene.hpp"
#include "server/multicast_path.hpp"
#include "server/process_memory.hpp"
#include "server/receiver.hpp"
#include "server/scene_device.hpp"
#include "server/servo_rig.hpp"
#include "server/servo_runner.hpp"
#include "server/session_log.hpp"
#include "server/stats_json.hpp"

namespace {

std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop.store(true); }

int run(const thx::srv::HapticdOptions& o) {
  using namespace thx;
  const scene::Scene sc = scene::loadScene(o.scene);
  for (const std::string& w : sc.warnings) std::fprintf(stderr, "hapticd: warning: %s\n", w.c_str());
  const std::string vrpn_address =
      srv::vrpnAddress(o, sc.device.type == scene::DeviceType::Vrpn ? sc.device.address : std::string());
  if (!vrpn_address.empty() && o.lockstep) {
    std::fprintf(stderr, "hapticd: %s: --lockstep needs the simulated device, the scene's is VRPN\n", o.scene.c_str());
    return 1;
  }
  const double period_s = 1.0 / sc.rates.servo_hz;
  // A mesh scene's mesh, built once for the scene's renderer and the simulated hand, whose script
  // presses and strokes on the mesh under its points (device/surface_height.hpp). Both outlive the
  // device, which is destroyed first.
  const std::shared_ptr<const srv::MeshGeometry> mesh = sc.surface.mesh ? srv::buildMeshGeometry(sc) : nullptr;
  std::unique_ptr<srv::MeshSurfaceHeight> hand_surface;
  if (mesh) {
    hand_surface = srv::handSurfaceFor(sc, *mesh);
    const bool simulated = o.device.rfind("replay:", 0) != 0 && vrpn_address.empty();
    if (simulated) srv::checkScriptOnMesh(sc, *hand_surface);
  }
  const srv::SceneDevice chosen =
      srv::makeSceneDevice(sc, o.device, vrpn_address, o.lockstep, hand_surface.get(), o.spin_ns);
  const dev::SimPhantom* sim = chosen.sim;
  const dev::ReplayDevice* replay = chosen.replay;
  if (replay && !o.quiet)
    std::fprintf(stderr, "hapticd: replaying %zu ticks (%.2f s) from %s\n", replay->size(), replay->durationS(),
                 o.device.substr(7).c_str());
  dev::HapticDevice& device = *chosen.device;
  const dev::DeviceSpec& spec = device.spec();

  std::unique_ptr<srv::PreparedScene> first = srv::prepareScene(sc, o.scene, spec, srv::scenePolicy(o), mesh);
  // Above the bound is the normal case with a real device (its vendor maximum counts on the hand's
  // damping): said in words with --verbose only; --strict-stability makes it an error (thrown above).
  if (o.verbose) {
    for (const std::string& line : srv::budgetReport(first->budget))
      std::fprintf(stderr, "hapticd: stability budget: %s\n", line.c_str());
  }
  srv::ServoRigConfig wiring = first->wiring;
  wiring.missed_mode = o.missed_mode;
  const std::size_t texture_bytes = first->surface.map->bytes();  // the first scene's
  srv::ServoRig rig(device, first->surface.surface, wiring, first->mesh_renderer.get());
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
  if (lcm && !o.quiet) std::fprintf(stderr, "hapticd: %s\n", srv::describeMulticastPath(o.lcm_url).c_str());
  if (lcm && ports.control_port > 0) {
    try {
      control_lcm = thx_msgs::openLcm(ports.controlUrl());
    } catch (const thx::Error& e) {  // clients then keep sending to the bus, which still works
      std::fprintf(stderr, "hapticd: warning: %s; clients send to the bus instead\n", e.what());
    }
  }
  srv::PublisherOptions po = srv::publisherOptions(o, sc.rates.servo_hz);
  po.device_name = vrpn_address.empty() ? "sim" : vrpn_address;
  po.device_names = sc.device.name;
  po.scene_name = first->surface.scene_name;
  po.texture_fingerprint = first->fingerprint;
  po.simulated_device = sim != nullptr || replay != nullptr;
  std::unique_ptr<srv::SessionRecorder> session;
  if (!o.record.empty()) {
    session = std::make_unique<srv::SessionRecorder>(o.record, po.simulated_device);  // throws with the path
    po.session = session.get();
  }
  po.fault_reset = &servo.faultResetSlot();
  // Owns every scene the servo renders from here on, the first one too; destroyed after the servo
  // thread has ended (declared after the rig, before the publisher that uses it).
  srv::SceneSwitcher switcher(servo.surfaceSwap(), sc, spec, std::move(first), srv::sceneSwitcherOptions(o));
  po.scene_loads = &switcher;
  if (control_lcm) {
    po.control_url = ports.controlUrl();
    po.control_lcm = control_lcm.get();
  }
  srv::Publisher publisher(ring, servo, rig.recorder(), lcm.get(), po);
  std::unique_ptr<srv::Receiver> receiver;
  if (lcm) receiver = std::make_unique<srv::Receiver>(*lcm, servo.clientForceSlot(), spec.peak_force_n);
  if (receiver && control_lcm) receiver->listenAlsoOn(*control_lcm);
  if (receiver) receiver->setFifoPriority(srv::ioThreadPriority(o));

  // VRPN apps: effects they command are rendered in the servo; reports come from its snapshots.
  srv::ExternalEffectRenderer external_effects(period_s);
  std::unique_ptr<srv::VrpnServer> vrpn_server;
  if (!o.vrpn_listen.empty()) {
    servo.attachExternalEffects(&external_effects);
    vrpn_server = std::make_unique<srv::VrpnServer>(servo.publishSnapshots(), &external_effects,
                                                    srv::vrpnServerOptions(o, spec, sc.rates.servo_hz));
    vrpn_server->start();  // throws with the address and reason if it cannot bind
    if (!o.quiet)
      std::fprintf(stderr, "hapticd: serving %s to VRPN apps at %s:%u (TCP and UDP)\n", o.vrpn_name.c_str(),
                   o.vrpn_address.ip.c_str(), unsigned(vrpn_server->port()));
  }

  // A simulated device runs its script; a real one runs until told to stop.
  // A replay runs to the end of its recording.
  const double duration_s =
      o.duration_s.value_or(sim ? sim->script().duration() + 0.5 : replay ? replay->durationS() : 0.0);

  publisher.start();
  if (receiver) receiver->start();
  srv::ServoRunner runner(servo, ring, {o.lockstep, srv::stopTickAfter(duration_s, sc.rates.servo_hz), &g_stop});
  const auto wall_start = std::chrono::steady_clock::now();
  runner.start(device, o.rt);
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
  device.close();
  if (session) {
    if (!o.quiet)
      std::fprintf(stderr, "hapticd: recorded %llu ticks to %s\n", (unsigned long long)session->ticks(),
                   session->path().c_str());
    if (ring.dropped() > 0)
      std::fprintf(stderr, "hapticd: warning: %s misses %llu ticks the publisher could not keep up with\n",
                   session->path().c_str(), (unsigned long long)ring.dropped());
  }
  if (!runner.error().empty()) {
    std::fprintf(stderr, "hapticd: %s\n", runner.error().c_str());
    return 1;
  }
  for (const std::string& w : runner.realtime().warnings) std::fprintf(stderr, "hapticd: warning: %s\n", w.c_str());

  srv::RunSummary summary;
  summary.scene = o.scene;
  summary.lockstep = o.lockstep;
  srv::addServoSummary(summary, rig);
  summary.device_time_s = runner.deviceTimeS(period_s);
  summary.wall_time_s = wall_s;
  summary.nominal_rate_hz = sc.rates.servo_hz;
  summary.realtime = runner.realtime();
  summary.memory = srv::readProcessMemory();
  summary.texture_bytes = texture_bytes;
  summary.publisher = publisher.counters();
  if (receiver) summary.client_forces_accepted = receiver->counters().accepted;
  summary.snapshots_dropped = ring.dropped();
  summary.flight_dir = o.flight_dir;
  summary.last_flight_dump = publisher.lastFlightDump();
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
  return thx::runProgram("hapticd", thx::srv::hapticdHelp(), argc, argv, [](const std::vector<std::string>& args) {
    const thx::srv::HapticdOptions options = thx::srv::parseHapticdOptions(args);
    thx::srv::prepareProcessForLockedMemory();  // small thread stacks, one malloc arena
    return run(options);  // scene, texture, hand script, device, files: each error names its source
  });
}
