// physics-client: Bullet bodies on the scene's textured plane, the pen following hapticd's device,
// its contact force sent back to hapticd, poses and contact events published. `--help`.
#include <lcm/lcm-cpp.hpp>
#include <time.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <memory>
#include <string>

#include "clients/physics_client/driver.hpp"
#include "clients/physics_client/lcm_io.hpp"
#include "clients/physics_client/options.hpp"
#include "clients/physics_client/pen_path.hpp"
#include "clients/physics_client/pose_csv.hpp"
#include "scenes/scene_loader.hpp"
#include "thx_client/client.hpp"

namespace {

using namespace thx::physclient;

std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop.store(true); }

constexpr char kDefaultUrl[] = "udpm://239.255.76.67:7667?ttl=0";

class NullSink final : public EventSink {};

std::int64_t nowNs() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return std::int64_t(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

void sleepUntil(std::int64_t deadline_ns) {
  timespec ts{};
  ts.tv_sec = time_t(deadline_ns / 1'000'000'000);
  ts.tv_nsec = long(deadline_ns % 1'000'000'000);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR && !g_stop.load()) {
  }
}

int runOffline(const Options& o, PhysicsScene& scene, const DriverOptions& d) {
  std::unique_ptr<lcm::LCM> lcm;
  std::unique_ptr<LcmSink> lcm_sink;
  NullSink null_sink;
  EventSink* sink = &null_sink;
  if (o.lcm_url && !o.no_lcm) {
    lcm = std::make_unique<lcm::LCM>(*o.lcm_url);
    if (!lcm->good()) {
      std::fprintf(stderr, "physics-client: LCM is not available at '%s'\n", o.lcm_url->c_str());
      return 1;
    }
    LcmSinkOptions so;
    so.client_id = o.client_id;
    so.send_force = false;  // nobody renders it: offline runs publish events only
    lcm_sink = std::make_unique<LcmSink>(*lcm, so);
    sink = lcm_sink.get();
  }
  std::unique_ptr<PenPath> path;
  const double dt = 1.0 / d.rate_hz;
  switch (o.pen_source) {
    case PenSource::ReplayLog:
      path = std::make_unique<PenPath>(loadSessionPen(o.pen_file, scene.scene().rates.servo_hz));
      break;
    case PenSource::Csv:
      path = std::make_unique<PenPath>(loadPenCsv(o.pen_file));
      break;
    case PenSource::Script: {
      std::vector<PenSample> s = penPathFromScript(scene, dt);
      if (s.size() < 2) {
        std::fprintf(stderr, "physics-client: %s: device.script: no press or stroke to follow; expected a hand script (or --no-pen)\n",
                     o.scene.c_str());
        return 1;
      }
      path = std::make_unique<PenPath>(std::move(s));
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
  const double duration = o.duration_s.value_or(path ? path->duration() + 1.0 : 0.0);
  const auto steps = std::int64_t(std::llround(duration * d.rate_hz));
  if (!o.quiet)
    std::fprintf(stderr, "physics-client: offline, %lld steps of %.3g ms (%.2f s), pen: %s\n", (long long)steps, dt * 1e3,
                 duration, path ? (std::to_string(path->size()) + " samples").c_str() : "none");
  Driver driver(scene, *sink, d);
  for (std::int64_t k = 0; k < steps && !g_stop.load(); ++k) {
    const double t = double(k) * dt;  // the pen pose the device had at the start of the step
    if (path)
      driver.step(path->at(t), path->tickAt(t));
    else
      driver.step(std::nullopt);
  }
  driver.flush();
  printSummary(stdout, driver.summary());
  if (!o.json.empty()) writeSummaryJson(o.json, o.scene, driver.summary());
  return 0;
}

int runOnline(const Options& o, PhysicsScene& scene, const DriverOptions& d) {
  const std::string url = o.lcm_url.value_or(kDefaultUrl);
  lcm::LCM lcm(url);
  if (!lcm.good()) {
    std::fprintf(stderr,
                 "physics-client: LCM is not available at '%s' (no multicast route? try `ip route add 224.0.0.0/4 dev lo` "
                 "as root, or --lcm-url)\n",
                 url.c_str());
    return 1;
  }
  thx::client::ClientOptions co;
  co.client_id = o.client_id;
  thx::client::Client client(lcm, co);
  client.subscribe("DEVICE_STATE", o.state_hz.value_or(d.rate_hz));
  LcmSinkOptions so;
  so.client_id = o.client_id;
  LcmSink lcm_sink(lcm, so);
  std::unique_ptr<PoseCsvSink> csv;
  if (!o.poses_csv.empty()) csv = std::make_unique<PoseCsvSink>(o.poses_csv);
  NullSink null_sink;
  TeeSink sink(lcm_sink, csv ? static_cast<EventSink&>(*csv) : null_sink);

  // What hapticd reports back: ticks where it applied a client force.
  long long states = 0, client_force_ticks = 0;
  double max_cmd_with_client = 0.0;
  client.onDeviceState([&](const thx_msgs::device_state_t& s, std::int64_t) {
    ++states;
    if (s.flags & thx_msgs::device_state_t::FLAG_CLIENT_FORCE) {
      ++client_force_ticks;
      max_cmd_with_client = std::max(
          max_cmd_with_client, std::sqrt(s.f_cmd_world[0] * s.f_cmd_world[0] + s.f_cmd_world[1] * s.f_cmd_world[1] +
                                         s.f_cmd_world[2] * s.f_cmd_world[2]));
    }
  });

  if (!o.quiet) std::fprintf(stderr, "physics-client: waiting for hapticd's DEVICE_STATE on %s\n", url.c_str());
  const std::int64_t give_up = nowNs() + std::int64_t(o.connect_timeout_s * 1e9);
  while (!client.latestDeviceState() && !g_stop.load()) {
    if (nowNs() > give_up) {
      std::fprintf(stderr,
                   "physics-client: no DEVICE_STATE from hapticd within %.3g s on %s (is hapticd running with LCM? "
                   "--connect-timeout S)\n",
                   o.connect_timeout_s, url.c_str());
      return 1;
    }
    client.poll(20);
  }
  if (!o.quiet) std::fprintf(stderr, "physics-client: connected; stepping at %g Hz\n", d.rate_hz);

  Driver driver(scene, sink, d);
  const std::int64_t period = std::int64_t(std::llround(1e9 / d.rate_hz));
  const std::int64_t steps = o.duration_s ? std::int64_t(std::llround(*o.duration_s * d.rate_hz)) : -1;
  std::int64_t next = nowNs();
  long long late = 0;
  std::int64_t last_tick = -1, stale_steps = 0;
  for (std::int64_t k = 0; (steps < 0 || k < steps) && !g_stop.load(); ++k) {
    next += period;
    const std::int64_t now = nowNs();
    if (now > next + 5 * period) {  // far behind: realign, no catch-up burst
      next = now;
      ++late;
    }
    sleepUntil(next);
    client.poll(0);
    std::optional<Eigen::Vector3d> tip;
    std::int64_t tick = -1;
    if (auto s = client.latestDeviceState()) {
      // Device states arrive in bursts; extrapolating the newest one by its age (same host, same
      // CLOCK_MONOTONIC; at most 20 ms) keeps the pen's motion, and so its velocity, smooth.
      const double age_s = std::clamp(double(nowNs() / 1000 - s->utime) * 1e-6, 0.0, 0.02);
      tip = Eigen::Vector3d(s->p_world[0], s->p_world[1], s->p_world[2]) +
            age_s * Eigen::Vector3d(s->v_world[0], s->v_world[1], s->v_world[2]);
      tick = s->tick;
    }
    if (tick == last_tick) ++stale_steps;
    last_tick = tick;
    driver.step(tip, tick);
  }
  lcm_sink.release(scene.penTip());
  driver.flush();
  printSummary(stdout, driver.summary());
  std::printf("  hapticd: %lld device states received, %lld with FLAG_CLIENT_FORCE (max |f_cmd| then %.4f N); "
              "%llu forces sent; %lld steps reused a pose, %lld realigned\n",
              states, client_force_ticks, max_cmd_with_client, (unsigned long long)lcm_sink.counters().forces,
              (long long)stale_steps, late);
  if (!o.json.empty()) writeSummaryJson(o.json, o.scene, driver.summary());
  return 0;
}

int run(const Options& o) {
  thx::scene::Scene scene_data = thx::scene::loadScene(o.scene);
  for (const std::string& w : scene_data.warnings) std::fprintf(stderr, "physics-client: warning: %s\n", w.c_str());
  SimOptions so;
  so.pen = o.pen;
  so.impact_min_speed_m_per_s = o.impact_min_speed;
  PhysicsScene scene(scene_data, so);
  DriverOptions d;
  d.rate_hz = o.rate_hz.value_or(scene_data.rates.physics_hz);
  d.pose_hz = o.pose_hz.value_or(scene_data.rates.visual_hz);
  d.contact_hz = std::min(d.rate_hz, o.contact_hz.value_or(scene_data.rates.audio_feed_hz));
  if (!o.quiet)
    std::fprintf(stderr, "physics-client: %s: %zu objects on a %s plane (%dx%d texels), pen %s\n", o.scene.c_str(),
                 scene_data.objects.size(), scene.surface().usesRelief() ? "relief" : "normal-mapped",
                 scene.surface().map().width(), scene.surface().map().height(),
                 o.pen.shape == PenShape::None ? "off" : o.pen.shape == PenShape::Sphere ? "sphere" : "capsule");
  return o.offline() ? runOffline(o, scene, d) : runOnline(o, scene, d);
}

}  // namespace

int main(int argc, char** argv) {
  struct sigaction sa {};
  sa.sa_handler = onSignal;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  Options o;
  try {
    o = parseOptions(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const UsageError& e) {
    std::fprintf(stderr, "physics-client: %s (see physics-client --help)\n", e.what());
    return 2;
  }
  if (o.help) {
    std::fputs(kHelp, stdout);
    return 0;
  }
  try {
    return run(o);
  } catch (const std::exception& e) {  // scene, texture and file errors all name their source
    std::fprintf(stderr, "physics-client: %s\n", e.what());
  }
  return 1;
}
