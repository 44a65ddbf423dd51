#include "server/scene_device.hpp"

#include <cmath>
#include <variant>

#include "base/number_text.hpp"
#include "device/device_specs.hpp"
#include "device/replay_device.hpp"
#include "device/sim_phantom.hpp"
#include "device/vrpn/vrpn_client_device.hpp"
#include "server/session_log.hpp"
#include "scenes/scene_frames.hpp"

namespace thx::srv {

dev::DeviceSpec deviceSpecFor(const scene::Scene& s) {
  const scene::DeviceModel& m = s.device.model;
  dev::DeviceSpec spec;
  spec.model = m.name;
  spec.peak_force_n = m.peak_force_n;
  spec.continuous_force_n = m.continuous_force_n;
  spec.max_stiffness_n_per_m = m.max_stiffness_n_per_m;
  spec.max_damping_ns_per_m = m.max_damping_ns_per_m;
  spec.workspace_radius_m = m.workspace_radius_m;
  spec.position_resolution_m = s.device.sim.encoder_resolution_m;
  spec.physical_damping_ns_per_m = dev::phantomDesktopSpec().physical_damping_ns_per_m;
  return spec;
}

dev::SimPhantomConfig simConfigFor(const scene::Scene& s, bool lockstep) {
  dev::SimPhantomConfig c;
  c.spec = deviceSpecFor(s);
  c.servo_period_ns = std::int64_t(1e9 / s.rates.servo_hz);
  c.integration_hz = s.device.sim.integration_hz;
  c.encoder_resolution_m = s.device.sim.encoder_resolution_m;
  c.device_mass_kg = s.device.sim.device_mass_kg;
  c.friction_n = s.device.sim.friction_n;
  c.hand_mass_kg = s.device.sim.hand_mass_kg;
  c.hand_stiffness_n_per_m = s.device.sim.hand_stiffness_n_per_m;
  c.hand_damping_ns_per_m = s.device.sim.hand_damping_ns_per_m;
  c.plane_to_world = scene::planeMapping(s.surface).plane_to_world;
  c.lockstep = lockstep;
  return c;
}

namespace {

// Every point of the script's contact steps (a stroke every millimetre), with its step's index.
template <class Fn>
void forEachContactPoint(const scene::Scene& scene, Fn fn) {
  for (std::size_t i = 0; i < scene.device.script.size(); ++i) {
    const scene::ScriptStep& step = scene.device.script[i];
    if (const auto* p = std::get_if<scene::PressStep>(&step)) fn(i, p->position_m);
    if (const auto* st = std::get_if<scene::StrokeStep>(&step)) {
      const int n = std::max(1, int(std::ceil((st->to_m - st->from_m).norm() / 1e-3)));
      for (int k = 0; k <= n; ++k) fn(i, Eigen::Vector2d(st->from_m + (st->to_m - st->from_m) * (double(k) / n)));
    }
    if (const auto* f = std::get_if<scene::PathFileStep>(&step)) {
      for (const dev::PathSample& s : dev::HandScript::loadPathCsv(f->path).samples) fn(i, s.p_m);
    }
  }
}

}  // namespace

dev::HandScript handScriptFor(const scene::Scene& s, const dev::SurfaceHeight* hand_surface) {
  dev::HandScriptOptions options;
  if (hand_surface) {
    double deepest = 0.0;  // below the hover height over the top
    forEachContactPoint(s, [&](std::size_t, const Eigen::Vector2d& p) {
      double z = 0.0;  // stays 0 where nothing is under p, as the script takes it (device/hand_script.hpp)
      hand_surface->heightAt(p, z);
      deepest = std::max(deepest, hand_surface->top() + options.hover_height_m - z);
    });
    options.approach_s = std::max(options.approach_s, deepest / kHandApproachSpeedMPerS);
  }
  std::vector<dev::HandStep> steps;
  steps.reserve(s.device.script.size());
  for (const scene::ScriptStep& step : s.device.script) {
    if (const auto* p = std::get_if<scene::PressStep>(&step)) {
      steps.emplace_back(std::in_place_type<dev::HandPress>, dev::HandPress{p->position_m, p->force_n, p->duration_s});
    } else if (const auto* st = std::get_if<scene::StrokeStep>(&step)) {
      steps.emplace_back(std::in_place_type<dev::HandStroke>,
                         dev::HandStroke{st->from_m, st->to_m, st->speed_m_per_s, st->force_n});
    } else if (const auto* h = std::get_if<scene::HoldStep>(&step)) {
      steps.emplace_back(std::in_place_type<dev::HandHold>, dev::HandHold{h->duration_s});
    } else if (const auto* m = std::get_if<scene::MoveStep>(&step)) {
      steps.emplace_back(std::in_place_type<dev::HandMove>, dev::HandMove{m->to_m, m->push_n, m->duration_s});
    } else if (const auto* f = std::get_if<scene::PathFileStep>(&step)) {
      dev::HandPath path = dev::HandScript::loadPathCsv(f->path);
      steps.emplace_back(std::in_place_type<dev::HandPath>, std::move(path));
    }
  }
  return dev::HandScript(std::move(steps), options);
}

RendererConfig rendererConfigFor(const scene::Scene& s) {
  RendererConfig c;
  c.stiffness_n_per_m = s.device.stiffnessNPerM();
  c.damping_ns_per_m = s.device.damping_ns_per_m;
  return c;
}

ServoRigConfig servoRigConfigFor(const scene::Scene& s) {
  ServoRigConfig c;
  c.renderer = rendererConfigFor(s);
  c.period_s = 1.0 / s.rates.servo_hz;
  c.passivity = true;
  c.quantisation_play = true;
  c.flight_record_ticks = std::size_t(s.rates.servo_hz);  // one second of ticks
  c.ring_records = 1024;  // 1 s of ticks: the publisher drains every 0.5 ms
  return c;
}

CapsuleToolConfig capsuleToolConfigFor(const scene::Tool& tool, const RendererConfig& renderer, double period_s) {
  CapsuleToolConfig c = couplingForServo(renderer, period_s);
  c.length_m = tool.length_m;
  c.radius_m = tool.radius_m;
  c.rot_stiffness_nm_per_rad = tool.rot_stiffness_nm_per_rad;
  return c;
}

SceneDevice makeSceneDevice(const scene::Scene& scene, const std::string& device_option,
                            const std::string& vrpn_address, bool lockstep, const dev::SurfaceHeight* hand_surface,
                            std::int64_t spin_ns, int replay_device) {
  const std::int64_t period_ns = std::int64_t(std::llround(1.0 / scene.rates.servo_hz * 1e9));
  SceneDevice d;
  if (device_option.rfind("replay:", 0) == 0) {
    dev::ReplayOptions ro;
    ro.period_ns = period_ns;
    ro.lockstep = lockstep;
    auto replay = std::make_unique<dev::ReplayDevice>(loadSessionTrajectory(device_option.substr(7), replay_device),
                                                      deviceSpecFor(scene), ro);
    d.replay = replay.get();
    d.device = std::move(replay);
  } else if (vrpn_address.empty()) {
    dev::SimPhantomConfig config = simConfigFor(scene, lockstep);
    config.surface_height = hand_surface;
    config.spin_ns = spin_ns;
    auto sim = std::make_unique<dev::SimPhantom>(config, handScriptFor(scene, hand_surface));
    d.sim = sim.get();
    d.device = std::move(sim);
  } else {
    vrpn::VrpnClientOptions vo;
    vo.period_ns = period_ns;
    vo.spin_ns = lockstep ? 0 : spin_ns;
    vo.request_rate_hz = scene.rates.servo_hz;  // a fresh pose every tick
    d.device = std::make_unique<vrpn::VrpnClientDevice>(vrpn_address, deviceSpecFor(scene), vo);
  }
  return d;
}

void checkScriptOnMesh(const scene::Scene& scene, const dev::SurfaceHeight& hand_surface) {
  forEachContactPoint(scene, [&](std::size_t step, const Eigen::Vector2d& p) {
    double z = 0.0;
    if (hand_surface.heightAt(p, z)) return;
    throw Error(Error::Kind::Config,
                scene.source + ": device.script[" + std::to_string(step) + "]: no part of the mesh lies under [" +
                    numberText(p.x()) + ", " + numberText(p.y()) +
                    "] (surface frame, seen from above): expected points over the mesh (scene-info prints its box)");
  });
}

}  // namespace thx::srv
