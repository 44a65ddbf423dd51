// physics-client: Bullet bodies on the scene's textured plane, a pen following each of hapticd's
// devices, each pen's contact force sent back to its device, poses and contact events published.
// `--help`.
#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "base/program_main.hpp"
#include "clients/physics_client/driver.hpp"
#include "clients/physics_client/lcm_io.hpp"
#include "clients/physics_client/options.hpp"
#include "clients/physics_client/pen_path.hpp"
#include "clients/physics_client/pose_csv.hpp"
#include "clients/physics_client/scene_follower.hpp"
#include "clients/physics_client/session_record.hpp"
#include "rt/clock.hpp"
#include "thx_client/app.hpp"
#include "thx_client/devices.hpp"
#include "thx_client/stop_signal.hpp"

namespace {

using namespace thx::physclient;

class NullSink final : public EventSink {};

// The devices of a --replay-log whose pens are simulated: --device N's, else every device its
// hellos name (a one-device log: device 0, every state).
std::vector<int> replayedDevices(const Options& o) {
  if (o.device) return {*o.device};
  std::vector<int> devices(std::size_t(loggedDeviceCount(o.pen_file)));
  for (std::size_t i = 0; i < devices.size(); ++i) devices[i] = int(i);
  return devices;
}

// The pen's orientation in device state `s` (a pen along its device's axis turns with it).
Eigen::Quaterniond orientationOf(const thx_msgs::device_state_t& s) {
  return Eigen::Quaterniond(s.q_world[0], s.q_world[1], s.q_world[2], s.q_world[3]);
}

// The tip of device state `s` now: device states arrive in bursts; extrapolating the newest one by
// its age (same host, same CLOCK_MONOTONIC; at most 20 ms) keeps the pen's motion, and so its
// velocity, smooth.
Eigen::Vector3d tipNow(const thx_msgs::device_state_t& s) {
  const double age_s = std::clamp(double(thx::rt::monotonicNowNs() / 1000 - s.utime) * 1e-6, 0.0, 0.02);
  return Eigen::Vector3d(s.p_world[0], s.p_world[1], s.p_world[2]) +
         age_s * Eigen::Vector3d(s.v_world[0], s.v_world[1], s.v_world[2]);
}

int runOffline(const Options& o, SceneFollower& sim) {
  PhysicsScene& scene = sim.physics();
  const DriverOptions& d = sim.rates();
  std::unique_ptr<lcm::LCM> lcm;
  std::unique_ptr<LcmSink> lcm_sink;
  NullSink null_sink;
  EventSink* sink = &null_sink;
  if (o.lcm_url && !o.no_lcm) {
    lcm = thx::client::openLcm(*o.lcm_url);
    LcmSinkOptions so;
    so.client_id = o.client_id;
    so.send_force = false;  // nobody renders it: offline runs publish events only
    lcm_sink = std::make_unique<LcmSink>(*lcm, so);
    sink = lcm_sink.get();
  }
  std::vector<PenPath> paths;  // pen i's path; empty: no pen
  const double dt = 1.0 / d.rate_hz;
  switch (o.pen_source) {
    case PenSource::ReplayLog: {
      const std::vector<int> devices = replayedDevices(o);
      for (std::vector<PenSample>& p : loadSessionPens(o.pen_file, scene.scene().rates.servo_hz, devices))
        paths.emplace_back(std::move(p));
      sim.setPens(devices);
      break;
    }
    case PenSource::Csv:
      paths.emplace_back(loadPenCsv(o.pen_file));
      break;
    case PenSource::Script: {
      std::vector<PenSample> s = penPathFromScript(scene, dt);
      if (s.size() < 2) {
        std::fprintf(stderr, "physics-client: %s: device.script: no press or stroke to follow; expected a hand script (or --no-pen)\n",
                     o.scene.c_str());
        return 1;
      }
      paths.emplace_back(std::move(s));
      break;
    }
    default:
      break;
  }
  std::unique_ptr<PoseCsvSink> csv;
  std::unique_ptr<TeeSink> tee;
  if (!o.poses_csv.empty()) {
    csv = std::make_unique<PoseCsvSink>(o.poses_csv);
    tee = std::make_unique<TeeSink>(*sink, *csv);
    sink = tee.get();
  }
  std::unique_ptr<RecordSink> record;
  std::unique_ptr<TeeSink> record_tee;
  if (!o.record.empty()) {
    if (!std::ofstream(o.record))  // before the run, not after it
      throw thx::Error(thx::Error::Kind::Io, "--record " + o.record + ": cannot create the log file");
    record = std::make_unique<RecordSink>(o.pen_source == PenSource::ReplayLog
                                              ? sessionClockOf(o.pen_file, sim.penDevices().front())
                                              : SessionClock{});
    record_tee = std::make_unique<TeeSink>(*sink, *record);
    sink = record_tee.get();
  }
  double longest = 0.0;
  std::string samples;  // "3751 samples", or one count per pen
  for (const PenPath& p : paths) {
    longest = std::max(longest, p.duration());
    samples += (samples.empty() ? "" : ", ") + std::to_string(p.size());
  }
  const double duration = o.duration_s.value_or(paths.empty() ? 0.0 : longest + 1.0);
  const auto steps = std::int64_t(std::llround(duration * d.rate_hz));
  if (!o.quiet)
    std::fprintf(stderr, "physics-client: offline, %lld steps of %.3g ms (%.2f s), %s: %s\n", (long long)steps, dt * 1e3,
                 duration, paths.size() > 1 ? (std::to_string(paths.size()) + " pens").c_str() : "pen",
                 paths.empty() ? "none" : (samples + " samples").c_str());
  sim.start(*sink);
  Driver& driver = sim.driver();
  std::vector<Driver::PenInput> pens(paths.size());
  for (std::int64_t k = 0; k < steps && !thx::client::stopRequested(); ++k) {
    const double t = double(k) * dt;  // the pen poses the devices had at the start of the step
    for (std::size_t i = 0; i < paths.size(); ++i) pens[i] = {paths[i].at(t), paths[i].tickAt(t), paths[i].orientationAt(t)};
    driver.step(pens);
  }
  driver.flush();
  if (record) {
    writeCombinedLog(o.pen_source == PenSource::ReplayLog ? o.pen_file : std::string(), record->events(), o.record);
    if (!o.quiet) std::fprintf(stderr, "physics-client: recorded %zu physics events to %s\n", record->events().size(), o.record.c_str());
  }
  printSummary(stdout, sim.summary());
  if (!o.json.empty()) writeSummaryJson(o.json, o.scene, sim.summary());
  return 0;
}

int runOnline(const Options& o, SceneFollower& sim) {
  thx::client::AppOptions ao;
  ao.client_id = o.client_id;
  ao.lcm_url = o.lcm_url.value_or(thx_msgs::kDefaultLcmUrl);
  ao.connect_timeout_s = o.connect_timeout_s;
  ao.scene = sim.identity();
  ao.allow_different_scene = o.allow_different_scene;
  // The device the kit follows (its callbacks, latestDeviceState()); waitForServer refuses an index
  // hapticd does not have. Every device's newest state is there either way (latestDeviceState(i)).
  ao.client.device = o.device.value_or(0);
  thx::client::ClientApp app(ao);
  thx::client::Client& client = app.client();
  double state_hz = o.state_hz.value_or(sim.rates().rate_hz);
  client.subscribe(thx_msgs::Stream::DeviceState, state_hz);

  RunSummary::HapticdLink link;  // what hapticd reports back: ticks where it applied a client force
  link.online = true;
  client.onDeviceState([&](const thx_msgs::device_state_t& s, std::int64_t) {
    ++link.device_states;
    if (!(s.flags & thx_msgs::device_state_t::FLAG_CLIENT_FORCE)) return;
    ++link.client_force_states;
    link.max_cmd_with_client_force_n =
        std::max(link.max_cmd_with_client_force_n, Eigen::Vector3d(s.f_cmd_world[0], s.f_cmd_world[1], s.f_cmd_world[2]).norm());
  });

  if (!o.quiet) std::fprintf(stderr, "physics-client: waiting for hapticd on %s\n", app.options().lcm_url.c_str());
  const auto hello = app.waitForServer();  // the same scene, or an error naming both
  if (!hello) return 0;                    // stopped
  const std::string server = hello->server_name.empty() ? std::string("hapticd") : hello->server_name;
  // A pen per device the hello names (a hello naming none: device 0), or --device N's alone.
  std::vector<int> devices = {ao.client.device};
  if (!o.device)
    for (int i = 1; i < int(thx::client::deviceNames(*hello).size()) && i < thx::client::kMaxDevices; ++i)
      devices.push_back(i);
  sim.setPens(devices);
  LcmSinkOptions so;
  so.client_id = o.client_id;
  so.server = &client;
  so.devices = devices;
  LcmSink lcm_sink(app.lcm(), so);
  std::unique_ptr<PoseCsvSink> csv;
  if (!o.poses_csv.empty()) csv = std::make_unique<PoseCsvSink>(o.poses_csv);
  NullSink null_sink;
  TeeSink sink(lcm_sink, csv ? static_cast<EventSink&>(*csv) : null_sink);

  if (!app.pollUntil([&] { return client.latestDeviceState().has_value(); }, o.connect_timeout_s)) {
    if (app.stopRequested()) return 0;
    throw thx::Error(thx::Error::Kind::Io, "no DEVICE_STATE from hapticd within " + std::to_string(o.connect_timeout_s) +
                                               " s on " + app.options().lcm_url +
                                               " (is hapticd running with LCM? --connect-timeout S)");
  }
  if (!o.quiet)
    std::fprintf(stderr, "physics-client: connected; stepping at %g Hz, %zu %s\n", sim.rates().rate_hz, devices.size(),
                 devices.size() == 1 ? "pen" : "pens (one per device)");

  sim.start(sink);
  // waitForServer checked the scene of the newest hello: changes after it are switches to follow.
  std::uint64_t scene_changes_seen = client.sceneChanges();
  bool said_keeping = false;
  std::int64_t last_tick = -1;
  std::vector<Driver::PenInput> pens(devices.size());
  for (;;) {
    // A switch ends the paced loop at a step boundary; the next scene gets a loop of its own rate.
    std::int64_t max_steps = -1;
    if (o.duration_s) {
      max_steps = std::llround((*o.duration_s - sim.summary().sim_time_s) * sim.rates().rate_hz);
      if (max_steps <= 0) break;
    }
    bool switch_due = false;
    const thx::client::LoopStats loop = app.runPaced(
        sim.rates().rate_hz,
        [&](const thx::rt::TickTiming&) {
          if (client.sceneChanges() != scene_changes_seen) {
            scene_changes_seen = client.sceneChanges();
            if (!o.allow_different_scene) {
              switch_due = true;
              return false;  // ends this loop before the step: the switch happens between steps
            }
            if (!said_keeping && !o.quiet)  // it differs on purpose: once is enough
              std::fprintf(stderr, "physics-client: %s switched to scene '%s'; keeping scene '%s' (--allow-different-scene)\n",
                           server.c_str(), client.serverScene()->name.c_str(), sim.identity().name.c_str());
            said_keeping = true;
          }
          for (std::size_t i = 0; i < devices.size(); ++i) {
            const auto s = client.latestDeviceState(devices[i]);  // none yet: the pen stays parked
            pens[i] = s ? Driver::PenInput{tipNow(*s), s->tick, orientationOf(*s)} : Driver::PenInput{};
          }
          if (pens[0].ref_tick == last_tick) ++link.stale_steps;  // the followed device's
          last_tick = pens[0].ref_tick;
          sim.driver().step(pens);
          return true;
        },
        max_steps);
    link.missed_steps += loop.missed;
    if (!switch_due) break;  // --duration reached, or a stop signal
    // The pen forces belong to the old scene: let go of the pens before anything else.
    lcm_sink.releaseAll(sim.physics());
    if (!sim.follow(*client.serverScene(), server)) continue;  // back on this scene already
    if (!o.state_hz && sim.rates().rate_hz != state_hz)
      client.subscribe(thx_msgs::Stream::DeviceState, state_hz = sim.rates().rate_hz);
    if (!o.quiet)
      std::fprintf(stderr, "physics-client: %s switched to scene '%s': following with %s (%zu objects, %g Hz; switch %d)\n",
                   server.c_str(), sim.identity().name.c_str(), sim.file().c_str(), sim.physics().scene().objects.size(),
                   sim.rates().rate_hz, sim.switches());
  }
  lcm_sink.releaseAll(sim.physics());
  sim.driver().flush();
  RunSummary summary = sim.summary();
  link.forces_sent = std::int64_t(lcm_sink.counters().forces);
  summary.hapticd = link;
  printSummary(stdout, summary);
  if (!o.json.empty()) writeSummaryJson(o.json, o.scene, summary);
  return 0;
}

int run(const Options& o) {
  SceneFollower sim(o);
  const PhysicsScene& scene = sim.physics();
  if (!o.quiet) {
    const std::string ground =
        scene.meshGround() ? "mesh of " + std::to_string(scene.meshGround()->sceneMesh().mesh.triangles.size()) + " triangles"
                           : "plane";
    std::fprintf(stderr, "physics-client: %s: %zu objects on a %s %s (%dx%d texels), pen %s\n", o.scene.c_str(),
                 scene.scene().objects.size(), scene.surface().usesRelief() ? "relief" : "normal-mapped", ground.c_str(),
                 scene.surface().map().width(), scene.surface().map().height(),
                 o.pen.shape == PenShape::None ? "off" : o.pen.shape == PenShape::Sphere ? "sphere" : "capsule");
  }
  return o.offline() ? runOffline(o, sim) : runOnline(o, sim);
}

}  // namespace

// Scene, texture, pen path, LCM and usage errors are thx::Errors naming their source.
int main(int argc, char** argv) {
  thx::client::installStopSignals();
  return thx::runProgram("physics-client", kHelp, argc, argv,
                         [](const std::vector<std::string>& args) { return run(parseOptions(args)); });
}
