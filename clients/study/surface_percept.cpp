#include "clients/study/surface_percept.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <variant>

#include "clients/study/ball_percept.hpp"
#include "clients/study/button_protocol.hpp"
#include "clients/study/sound_percept.hpp"
#include "device/sim_phantom.hpp"
#include "scenes/scene_loader.hpp"
#include "server/prepared_scene.hpp"
#include "server/scene_device.hpp"

namespace thx::study {

Cue cueOf(int feature) {
  if (feature == kSoundPitch || feature == kSoundRing) return Cue::Sound;
  if (feature == kBallShake || feature == kBallSlip) return Cue::Ball;
  return Cue::Pen;
}

bool cueOn(const Cues& cues, Cue cue) {
  return cue == Cue::Sound ? cues.sound : cue == Cue::Ball ? cues.ball : cues.pen;
}

dev::HandScript explorationScript(double extent_m, double force_n) {
  const double a = 0.25 * extent_m;  // well inside the surface, clear of its edges
  std::vector<dev::HandStep> steps;
  steps.emplace_back(std::in_place_type<dev::HandHold>, dev::HandHold{0.6});  // the safety stage's engage ramp (0.5 s) passes
  // One diagonal stroke, so the tip crosses features along both axes.
  steps.emplace_back(std::in_place_type<dev::HandStroke>, dev::HandStroke{{-a, -0.5 * a}, {a, 0.5 * a}, 0.08, force_n});
  return dev::HandScript(std::move(steps));
}

namespace {

// The scene prepared as hapticd prepares it, on a lock-step simulated PHANToM driven by `script`;
// calls `each` with every tick record and the simulated time, for `duration_s` or until `each`
// returns false.
void runServo(const std::string& scene_path, const Cues& cues, dev::HandScript script, double duration_s,
              const std::function<bool(const srv::TickRecord&, double)>& each) {
  const scene::Scene sc = scene::loadScene(scene_path);
  dev::SimPhantom device(srv::simConfigFor(sc, /*lockstep=*/true), std::move(script));
  srv::ScenePolicy policy;
  if (!cues.pen) policy.stiffness_fraction = 0.0;  // the pen still moves, nothing pushes back (as NAME.nopen)
  const auto prepared = srv::prepareScene(sc, scene_path, {device.spec()}, policy);
  srv::ServoRig rig(device, prepared->surface.surface, prepared->devices[0].wiring);
  device.open();
  const double period_s = prepared->devices[0].wiring.period_s;
  const long ticks = long(std::ceil(duration_s / period_s));
  for (long k = 0; k < ticks; ++k)
    if (!each(rig.tickAndDrain(), double(k + 1) * period_s)) return;
}

double norm3(const double* v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

}  // namespace

Percept measureSurface(const std::string& scene_path, const Cues& cues) {
  const scene::Scene sc = scene::loadScene(scene_path);
  Percept p;
  const scene::SceneSurface surf = scene::buildSceneSurface(sc);
  p.representation = surf.map->isRelief() ? Representation::Relief : Representation::Normal;
  if (cues.sound) {
    if (const std::optional<SoundPercept> heard = hearSurface(scene_path)) {
      p.features[kSoundPitch] = heard->pitch_log10_hz;
      p.features[kSoundRing] = heard->ring_log10_s;
    }
  }
  if (cues.ball) {
    if (const std::optional<BallPercept> seen = watchBall(sc)) {
      p.features[kBallShake] = seen->shake_log10;
      p.features[kBallSlip] = seen->slip;
    }
  }
  // The pen: what the servo renders along the exploration stroke, whatever the cues; without
  // the pen's force there is nothing to feel (below 0.05 N mean, no feature).
  const dev::HandScript script = explorationScript(sc.surface.size_m.minCoeff());
  const double duration = script.duration();
  double sum_lat2 = 0.0, sum_n = 0.0, sum_n2 = 0.0;
  long count = 0;
  runServo(scene_path, cues, script, duration, [&](const srv::TickRecord& r, double t) {
    if (t < 0.8 || !r.in_contact) return true;  // after the engage ramp, while touching
    const double* n = r.n_geom_world;
    const double fn = r.f_out[0] * n[0] + r.f_out[1] * n[1] + r.f_out[2] * n[2];
    const double lat[3] = {r.f_out[0] - fn * n[0], r.f_out[1] - fn * n[1], r.f_out[2] - fn * n[2]};
    const double l = norm3(lat);
    sum_lat2 += l * l;
    sum_n += fn;
    sum_n2 += fn * fn;
    ++count;
    return true;
  });
  p.explore_s = duration;
  if (count > 0) {
    const double mean_n = sum_n / double(count);
    if (mean_n > 0.05) {
      p.features[kPenLateral] = std::log10(std::max(1e-4, std::sqrt(sum_lat2 / double(count)) / mean_n));
      const double var = std::max(0.0, sum_n2 / double(count) - mean_n * mean_n);
      p.features[kPenNormalVar] = std::sqrt(var) / mean_n;
    }
  }
  return p;
}

Percept withoutSoundOrBall(Percept all, const Cues& cues) {
  for (int f = 0; f < kFeatureCount; ++f)
    if (cueOf(f) != Cue::Pen && !cueOn(cues, cueOf(f))) all.features[std::size_t(f)].reset();
  return all;
}

ButtonRun pressButton(const std::string& scene_path, const Cues& cues, int nexts) {
  // Quick taps at the surface's centre (a short push is a NEXT), then a hold (CONFIRM). The sim's
  // button is down while its hand pushes, so a tap is a quick push: short approach and ramps.
  dev::HandScriptOptions quick;
  quick.hover_height_m = 0.002;
  quick.approach_s = 0.05;
  quick.force_ramp_s = 0.03;
  std::vector<dev::HandStep> steps;
  for (int i = 0; i < nexts; ++i) steps.emplace_back(std::in_place_type<dev::HandPress>, dev::HandPress{{0.0, 0.0}, 1.0, 0.1});
  steps.emplace_back(std::in_place_type<dev::HandPress>, dev::HandPress{{0.0, 0.0}, 1.0, 1.0});
  steps.emplace_back(std::in_place_type<dev::HandHold>, dev::HandHold{0.2});
  dev::HandScript script(std::move(steps), quick);
  ButtonProtocol protocol;
  ButtonRun out;
  runServo(scene_path, cues, script, script.duration(), [&](const srv::TickRecord& r, double t) {
    const ButtonEvent e = protocol.update(t, r.buttons);
    if (e == ButtonEvent::Next) ++out.nexts;
    if (e == ButtonEvent::Confirm) out.confirm_s = t;
    return !out.confirm_s;  // the answer is given: the trial ends
  });
  return out;
}

}  // namespace thx::study
