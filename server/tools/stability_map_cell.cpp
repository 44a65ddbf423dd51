#include "server/tools/stability_map_cell.hpp"

#include "server/paper_loop.hpp"

#include "base/error.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "device/sim_dynamics.hpp"
#include "server/tools/stability_map_rig.hpp"
#include "textures/textured_surface.hpp"

namespace thx::srv::stab {

namespace {

// The hand as a linear force field around a fixed target: F(x) = F0 + A (x - x_target) at the
// target's velocity (no damping term). Read from SimDynamics so the potential follows whatever
// the hand model does (its spring is anisotropic while it pushes).
struct HandField {
  Eigen::Vector3d f0 = Eigen::Vector3d::Zero();
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d target = Eigen::Vector3d::Zero();

  HandField(const dev::SimDynamics& dynamics, const dev::HandTarget& t) : target(t.p_m) {
    dev::SimBodyState s;
    s.x_m = t.p_m;
    s.v_m_per_s = t.v_m_per_s;
    f0 = dynamics.handForce(s, t);
    constexpr double kProbeM = 1e-3;  // the field is linear: any step gives the same matrix
    for (int i = 0; i < 3; ++i) {
      dev::SimBodyState p = s;
      p.x_m[i] += kProbeM;
      a.col(i) = (dynamics.handForce(p, t) - f0) / kProbeM;
    }
  }
  double potential(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d d = x - target;
    return -f0.dot(d) - 0.5 * d.dot(a * d);
  }
};

}  // namespace

const char* penToolName(PenTool tool) {
  switch (tool) {
    case PenTool::Point: return "point";
    case PenTool::Capsule: return "capsule";
    case PenTool::CapsuleAcross: return "capsule-across";
  }
  return "?";
}

std::string Mitigations::name() const {
  if (paper_loop) return smoothing ? "paper+smoothing" : "paper";
  if (crease && passivity && smoothing) return "all";
  std::string s;
  const auto add = [&](bool on, const char* n) {
    if (!on) return;
    if (!s.empty()) s += "+";
    s += n;
  };
  add(crease, "crease");
  add(passivity, "passivity");
  add(smoothing, "smoothing");
  return s.empty() ? "none" : s;
}

Mitigations Mitigations::fromIndex(int index) {
  return Mitigations{(index & 1) != 0, (index & 2) != 0, (index & 4) != 0, (index & 8) != 0};
}

HandParams defaultHand() {
  const dev::SimPhantomConfig c;
  return HandParams{"default", c.hand_mass_kg, c.hand_stiffness_n_per_m, c.hand_damping_ns_per_m, c.friction_n};
}

HandParams lightGripHand() { return HandParams{"light", 0.05, 100.0, 0.5, 0.06}; }

HandParams handByName(const std::string& name) {
  if (name == "default") return defaultHand();
  if (name == "light") return lightGripHand();
  throw thx::Error(thx::Error::Kind::Config, "hand '" + name + "': expected 'default' or 'light'");
}

dev::SimPhantomConfig simConfigFor(const HandParams& hand) {
  dev::SimPhantomConfig c;
  c.hand_mass_kg = hand.mass_kg;
  c.hand_stiffness_n_per_m = hand.stiffness_n_per_m;
  c.hand_damping_ns_per_m = hand.damping_ns_per_m;
  c.friction_n = hand.friction_n;
  c.lockstep = true;
  return c;
}

CellResult simulateCell(const CellParams& params, const ValleyMap& valley, const CellSetup& setup,
                        const TraceFn& trace) {
  if (valley.angle_deg != params.angle_deg || valley.smoothed != params.mitigations.smoothing)
    throw thx::Error(thx::Error::Kind::Config, "simulateCell: the valley map does not match the cell");
  const ValleyGeometry& g = setup.geometry;
  tex::PlaneMapping mapping;
  mapping.size_m = {g.extentM(), g.extentM()};
  const tex::SampleOptions sampling{tex::Filter::Bilinear, tex::Address::Wrap};
  const tex::TexturedSurface surface(*valley.map, mapping, sampling, params.relief);

  const double floor_x = g.floorXM();
  const double aim_x = floor_x + setup.aim_offset_m;
  CellResult result;
  result.params = params;
  result.floor_height_m = surface.at(aim_x, 0.0).height_m;

  const bool capsule = setup.tool != PenTool::Point;
  if (capsule && (params.mitigations.crease || params.mitigations.paper_loop))
    throw thx::Error(thx::Error::Kind::Config, "simulateCell: mitigations '" + params.mitigations.name() +
                                                   "': a capsule takes none, passivity and smoothing only");
  if (capsule && !params.relief)
    throw thx::Error(thx::Error::Kind::Config, "simulateCell: a capsule needs the relief representation");
  dev::SimPhantomConfig sim = simConfigFor(setup.hand);
  if (setup.tool == PenTool::CapsuleAcross)  // the shaft along -x from the tip, level
    sim.pen_orientation = Eigen::Quaterniond(Eigen::AngleAxisd(-0.5 * std::numbers::pi, Eigen::Vector3d::UnitY()));
  // The hand's frame: where the pen's point rests, so that the hand's spring pulls no harder on
  // one pen than another: the floor for the point; a capsule's ball centre r / sin(half the
  // opening) above it upright, in contact with both walls; lying across, the radius above the
  // crests. (Anchored at the floor, the default hand's normal spring, 30 N/m, pulled the ball
  // 4 mm above a 60 degree floor down with 0.12 N more than the point pen felt, and 2 N pushes
  // reached the continuous-force limit inside the window.)
  double rest_m = result.floor_height_m;
  if (setup.tool == PenTool::Capsule)
    rest_m += setup.capsule_radius_m / std::sin(0.5 * params.angle_deg * std::numbers::pi / 180.0);
  if (setup.tool == PenTool::CapsuleAcross) rest_m += valley.depth_m + setup.capsule_radius_m;
  sim.plane_to_world = Eigen::Translation3d(0.0, 0.0, rest_m);
  dev::HandScriptOptions hand_options;
  hand_options.hover_height_m = setup.hover_m;
  dev::HandScript script({dev::HandHold{setup.settle_s}, dev::HandPress{{aim_x, 0.0}, params.push_force_n, setup.duration_s}},
                         hand_options);

  RigOptions rig_options;
  result.stiffness_n_per_m = params.stiffness_fraction * sim.spec.max_stiffness_n_per_m;
  rig_options.stiffness_n_per_m = result.stiffness_n_per_m;
  rig_options.damping_ns_per_m = setup.virtual_damping_ns_per_m;
  rig_options.crease_handling = params.mitigations.crease;
  rig_options.passivity = params.mitigations.passivity;
  rig_options.recovery_ticks = setup.recovery_ticks;
  rig_options.sided_ridges = setup.sided_ridges;
  if (params.mitigations.paper_loop) {
    rig_options.crease_handling = false;
    rig_options.passivity = false;
    rig_options.recovery_ticks = 0;
    rig_options.plane_hold_ticks = planeHoldTicks(1e9 / double(sim.servo_period_ns), setup.plane_rate_hz);
  }
  if (capsule) {
    RendererConfig renderer;  // the coupling is the renderer's spring, as in hapticd
    renderer.stiffness_n_per_m = result.stiffness_n_per_m;
    renderer.damping_ns_per_m = setup.virtual_damping_ns_per_m;
    CapsuleToolConfig tool = couplingForServo(renderer, double(sim.servo_period_ns) * 1e-9);
    tool.length_m = setup.capsule_length_m;
    tool.radius_m = setup.capsule_radius_m;
    rig_options.capsule = tool;
  }
  SimRig rig(surface, sim, std::move(script), rig_options);
  const dev::SimDynamics dynamics(sim);

  const long total_ticks = std::lround(setup.duration_s / rig.periodS());
  const long window_ticks = std::min(total_ticks - 1, std::lround(setup.window_s / rig.periodS()));
  const long first_window_tick = total_ticks - window_ticks;

  std::vector<WindowSample> samples;
  samples.reserve(std::size_t(window_ticks));
  WindowEnergy energy;
  double peak_force_run_n = 0.0;
  double dissipated_at_start_j = 0.0;
  std::unique_ptr<HandField> hand;
  const double mass_kg = dynamics.massKg();
  const auto kinetic = [&](const dev::SimTruth& t) { return 0.5 * mass_kg * t.v_world_m_per_s.squaredNorm(); };

  for (long k = 0; k < total_ticks; ++k) {
    const TickRecord& r = rig.tick();
    const dev::SimTruth& truth = rig.truth();
    if (trace) trace(r, truth);
    const Eigen::Vector3d f_out(r.f_out[0], r.f_out[1], r.f_out[2]);
    peak_force_run_n = std::max(peak_force_run_n, f_out.norm());
    if (k == first_window_tick - 1) {  // the state the window starts from
      hand = std::make_unique<HandField>(dynamics, truth.hand_target_world);
      energy.kinetic_start_j = kinetic(truth);
      energy.hand_potential_start_j = hand->potential(truth.p_world_m);
      dissipated_at_start_j = rig.passivity().dissipatedEnergy();
    }
    if (k < first_window_tick) continue;
    energy.motor_work_j += truth.motor_work_j;
    WindowSample w;
    w.t_s = truth.t_s;
    w.p_m = surface.toLocal(truth.p_world_m);
    w.f_out_n = surface.directionToLocal(f_out);
    w.depth_m = r.depth_m;
    w.in_contact = r.in_contact;
    w.recovering = r.recovering;
    // 0.1 % below the peak: the safety stage clamps to exactly the peak, the motors clip to it.
    w.at_peak = truth.motor_saturated || f_out.norm() >= 0.999 * sim.spec.peak_force_n;
    w.peak_clamped = (r.safety_flags & kSafetyPeakClamped) != 0;
    w.continuous_limited = (r.safety_flags & kSafetyContinuousLimited) != 0;
    w.rate_limited = (r.safety_flags & kSafetyRateLimited) != 0;
    w.passivity_active = r.pc_damping_ns_per_m > 0.0;
    samples.push_back(w);
  }
  const dev::SimTruth& end = rig.truth();
  energy.kinetic_end_j = kinetic(end);
  energy.hand_potential_end_j = hand ? hand->potential(end.p_world_m) : 0.0;
  energy.passivity_dissipated_j = rig.passivity().dissipatedEnergy() - dissipated_at_start_j;

  result.metrics = measureWindow(samples, energy, aim_x, floor_x, sim.encoder_resolution_m, peak_force_run_n);
  result.metrics.held_depth_m = params.push_force_n / result.stiffness_n_per_m;
  result.metrics.push_force_n = params.push_force_n;
  result.metrics.continuous_force_n = sim.spec.continuous_force_n;
  classify(result.metrics, setup.thresholds, g.period_m);
  return result;
}

}  // namespace thx::srv::stab
