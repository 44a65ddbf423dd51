// Stability-map cells and the hard cases around them (issue 3), lock-step and deterministic:
//  - the map reproduces the problem: a steep valley at full stiffness without mitigations is not
//    stable; the same cell with crease handling + passivity is;
//  - grazing normals, texture edges (clamp), the probe outside the plane rectangle (wrap vs
//    clamp), a 2 m/s stroke across many valleys: never a NaN, never more than the peak force;
//  - non-finite device readings: the commanded force goes to zero and the safety stage disengages;
//  - stiffness beyond the sampled-wall bound: reported, and an error under the strict policy;
//  - the metrics' energy bookkeeping, the verdict rules, determinism across threads.
// Every cell is 3 simulated seconds (~3 ms optimised); the file stays well under 20 s with ASan.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "device/device_specs.hpp"
#include "server/proxy_renderer.hpp"
#include "server/stability_budget.hpp"
#include "server/tools/stability_map_cell.hpp"
#include "server/tools/stability_map_rig.hpp"
#include "server/tools/stability_map_sweep.hpp"
#include "textures/generators.hpp"
#include "tests/support/sanitized_build.hpp"

namespace test_stability_cells {

using namespace thx;
using namespace thx::srv::stab;

namespace {

constexpr double kPeakN = 7.9;  // PHANToM Desktop

CellParams cell(double angle, double k, double f, bool relief, const char* mitigations) {
  CellParams p;
  p.angle_deg = angle;
  p.stiffness_fraction = k;
  p.push_force_n = f;
  p.relief = relief;
  const std::string m = mitigations;
  p.mitigations.paper_loop = m.rfind("paper", 0) == 0;
  p.mitigations.crease = m.find("crease") != std::string::npos || m == "all";
  p.mitigations.passivity = m.find("passivity") != std::string::npos || m == "all";
  p.mitigations.smoothing = m.find("smoothing") != std::string::npos || m == "all";
  return p;
}

CellResult simulate(const CellParams& p, const CellSetup& setup = CellSetup{}) {
  const ValleyMap valley = buildValleyMap(p.angle_deg, p.mitigations.smoothing, setup.geometry);
  return simulateCell(p, valley, setup);
}

// What a free-form run (any surface, any script) must never do.
struct RunCheck {
  bool all_finite = true;       // commanded force and true state
  double max_force_out_n = 0;   // |F_out|, after safety
  double max_motor_n = 0;       // |F| the simulated motors applied
  double mean_normal_force_n = 0;  // over the last `tail` ticks, along the plane's normal
  int nonfinite_commands = 0;
  long contact_ticks = 0;
};

RunCheck run(const tex::TexturedSurface& surface, dev::SimPhantomConfig sim, dev::HandScript script,
             const RigOptions& options, long ticks, long tail = 500) {
  SimRig rig(surface, sim, std::move(script), options);
  RunCheck c;
  double fz_sum = 0;
  for (long k = 0; k < ticks; ++k) {
    const srv::TickRecord& r = rig.tick();
    const Eigen::Vector3d f(r.f_out[0], r.f_out[1], r.f_out[2]);
    const dev::SimTruth& t = rig.truth();
    c.all_finite = c.all_finite && f.allFinite() && t.p_world_m.allFinite() && t.v_world_m_per_s.allFinite();
    c.max_force_out_n = std::max(c.max_force_out_n, f.norm());
    c.max_motor_n = std::max(c.max_motor_n, t.motor_force_n.norm());
    c.contact_ticks += r.in_contact ? 1 : 0;
    if (k >= ticks - tail) fz_sum += surface.directionToLocal(f).z();
  }
  c.mean_normal_force_n = fz_sum / double(tail);
  c.nonfinite_commands = int(rig.truth().nonfinite_commands);
  return c;
}

dev::HandScript pressAt(double x, double y, double force_n, double duration_s) {
  return dev::HandScript({dev::HandHold{0.5}, dev::HandPress{{x, y}, force_n, duration_s}});
}

RigOptions rigOptions(bool crease, bool passivity) {
  RigOptions o;
  o.stiffness_n_per_m = 1000.0;
  o.damping_ns_per_m = 1.0;
  o.crease_handling = crease;
  o.passivity = passivity;
  return o;
}

tex::TextureMap valleyMap(double angle_deg, double extent_m, int size) {
  tex::GenerateRequest g;
  g.kind = "vvalley";
  g.size = size;
  g.params = {{"angle_deg", angle_deg}, {"period", 0.004}, {"extent", extent_m}};
  return tex::generate(g);
}

tex::PlaneMapping squareMapping(double extent_m) {
  tex::PlaneMapping m;
  m.size_m = {extent_m, extent_m};
  return m;
}

}  // namespace

// ---- the map reproduces the problem, and the mitigations remove it ----------------------------

TEST(StabilityCells, SteepValleyFullStiffnessWithoutMitigationsIsNotStable) {
  for (const bool relief : {true, false}) {
    const CellResult r = simulate(cell(60, 1.0, 1.0, relief, "none"));
    EXPECT_NE(r.metrics.verdict, Verdict::Stable) << (relief ? "relief: " : "normal: ") << r.metrics.reason;
    EXPECT_GT(r.metrics.lateral_pp_m, 1e-3) << r.metrics.reason;  // millimetres across the valley
    EXPECT_GT(r.metrics.lateral_force_pp_n, 1.0);
    // Only the motors can feed a sustained oscillation against the hand's damping.
    EXPECT_GT(r.metrics.energy_injected_j, 1e-3);
    EXPECT_TRUE(r.metrics.finite);
  }
}

TEST(StabilityCells, SameCellWithCreaseAndPassivityIsStable) {
  for (const bool relief : {true, false}) {
    const CellResult r = simulate(cell(60, 1.0, 1.0, relief, "crease+passivity"));
    EXPECT_EQ(r.metrics.verdict, Verdict::Stable) << r.metrics.reason;
    EXPECT_LT(r.metrics.lateral_pp_m, 2 * 2.3e-5);
    EXPECT_LT(std::fabs(r.metrics.energy_injected_j), 1e-4);
    // The pen rests on the floor and the wall carries the push (minus the hand's normal spring).
    EXPECT_GT(r.metrics.normal_force_mean_n, 0.8);
    EXPECT_LT(r.metrics.normal_force_mean_n, 1.05);
  }
}

// The paper's own loop (one plane per 10 ms frame, no recovery rule, no passivity controller) is
// the map's baseline, and its own mitigation, smoothing the normals (sigma = 2 texels) with a lower
// stiffness, is judged on it (docs/stability.md, "The paper's loop and its mitigation"): at 80 deg
// it works only with both parts; at 60 deg it does not work even at 0.1 x K, where crease handling
// with the passivity controller is stable at full stiffness. Its cost in detail: the smoothed
// 60 deg valley's deepest texel is 13 % shallower, its floor rounded over several texels.
TEST(StabilityCells, ThePapersMitigationOnThePapersLoop) {
  const auto verdict = [](double angle, double k, const char* m) { return simulate(cell(angle, k, 1.0, true, m)).metrics; };
  EXPECT_EQ(verdict(80, 1.0, "paper").verdict, Verdict::Unstable);
  EXPECT_EQ(verdict(80, 1.0, "paper+smoothing").verdict, Verdict::Unstable);  // smoothing alone: not enough
  const CellMetrics both = verdict(80, 0.25, "paper+smoothing");
  EXPECT_EQ(both.verdict, Verdict::Stable) << both.reason;  // with a quarter of the stiffness: stable
  const CellMetrics steep = verdict(60, 0.1, "paper+smoothing");
  EXPECT_EQ(steep.verdict, Verdict::LimitCycle) << steep.reason;
  EXPECT_GT(steep.lateral_pp_m, 1e-3);          // a millimetre-scale wobble across the floor
  EXPECT_GT(steep.depth_mean_m, 3.46e-3 * 2.0);  // and the pen twice the valley's depth into the surface

  const ValleyGeometry g;
  const ValleyMap sharp = buildValleyMap(60, false, g), smoothed = buildValleyMap(60, true, g);
  double sharp_depth = 0, smoothed_depth = 0;
  for (int i = 0; i < sharp.map->width(); ++i) {
    sharp_depth = std::max(sharp_depth, double(sharp.map->depth(i, 0)));
    smoothed_depth = std::max(smoothed_depth, double(smoothed.map->depth(i, 0)));
  }
  EXPECT_NEAR(smoothed_depth / sharp_depth, 0.87, 0.01) << sharp_depth << " -> " << smoothed_depth;
}

TEST(StabilityCells, SimulationIsDeterministicAndIndependentOfThreads) {
  std::vector<CellParams> cells = {cell(40, 1.0, 1.0, true, "none"), cell(40, 1.0, 1.0, true, "all"),
                                   cell(120, 0.5, 2.0, false, "passivity"),
                                   cell(120, 0.5, 2.0, false, "crease+smoothing")};
  if (thx::test::kSanitized) cells = {cells[0], cells[2]};  // two cells still split across the threads
  const CellSetup setup;
  const std::vector<CellResult> one = runSweep(cells, setup, 1);
  const std::vector<CellResult> two = runSweep(cells, setup, 2);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].metrics.verdict, two[i].metrics.verdict);
    EXPECT_EQ(one[i].metrics.lateral_pp_m, two[i].metrics.lateral_pp_m);  // bit for bit
    EXPECT_EQ(one[i].metrics.energy_injected_j, two[i].metrics.energy_injected_j);
  }
}

// ---- the metrics ---------------------------------------------------------------------------------

TEST(StabilityCells, EnergyInjectedMatchesWhatTheHandAndMechanismDissipate) {
  // A pen at rest: nothing dissipated, so nothing injected, although the motors hold ~1 N.
  const CellResult rest = simulate(cell(60, 1.0, 1.0, true, "crease"));
  EXPECT_LT(std::fabs(rest.metrics.energy_injected_j), 1e-5);
  // A limit cycle: the hand's damping alone burns at least b <v^2> T_window (the mechanism's
  // friction and damping burn more on top), and the motors supplied it.
  const CellResult cycling = simulate(cell(60, 1.0, 1.0, true, "none"));
  const double omega = 2 * 3.14159265358979 * cycling.metrics.oscillation_hz;
  const double hand_damping_j = 3.0 * omega * omega * cycling.metrics.lateral_rms_m * cycling.metrics.lateral_rms_m *
                                cycling.metrics.window_s;
  EXPECT_GT(cycling.metrics.energy_injected_j, 0.5 * hand_damping_j);
  EXPECT_GT(cycling.metrics.motor_work_j, 0.5 * cycling.metrics.energy_injected_j);
}

TEST(StabilityCells, VerdictRules) {
  const Thresholds t;
  CellMetrics m;
  m.finite = true;
  m.crossings = m.normal_crossings = 100;
  classify(m, t, 0.004);
  EXPECT_EQ(m.verdict, Verdict::Stable);

  m.lateral_force_pp_n = 0.3;  // a buzz without visible motion is still a limit cycle
  classify(m, t, 0.004);
  EXPECT_EQ(m.verdict, Verdict::LimitCycle);

  m.lateral_force_pp_n = 0.0;
  m.normal_pp_m = 1e-4;
  m.normal_crossings = 2;  // ... but slow drift is not
  classify(m, t, 0.004);
  EXPECT_EQ(m.verdict, Verdict::Stable) << m.reason;
  m.motor_work_j = 2e-3;  // ... unless the motors feed it: a slow cycle
  classify(m, t, 0.004);
  EXPECT_EQ(m.verdict, Verdict::LimitCycle) << m.reason;
  m.motor_work_j = 0.0;
  m.normal_pp_m = 0.0;

  m.lateral_pp_m = m.lateral_pp_second_m = 3e-4;
  m.lateral_pp_first_m = 1e-4;  // growing
  classify(m, t, 0.004);
  EXPECT_EQ(m.verdict, Verdict::Unstable);

  m.lateral_pp_first_m = 3e-4;
  classify(m, t, 0.004);
  EXPECT_EQ(m.verdict, Verdict::LimitCycle);

  m.excursion_m = 1.5e-3;  // thrown up the walls
  classify(m, t, 0.004);
  EXPECT_EQ(m.verdict, Verdict::Unstable);

  m.excursion_m = 0.0;
  m.at_peak_fraction = 0.01;
  classify(m, t, 0.004);
  EXPECT_EQ(m.verdict, Verdict::Unstable);

  m.at_peak_fraction = 0.0;
  m.finite = false;
  classify(m, t, 0.004);
  EXPECT_EQ(m.verdict, Verdict::Unstable);

  // The continuous-force limit held the force down and the pen sank more than 1 mm past where the
  // spring holds the push: the device cannot hold it, whatever the pen does meanwhile.
  m.finite = true;
  m.held_depth_m = 1e-3;  // 1 N on 1000 N/m, below the continuous 1.185 N
  m.push_force_n = 1.0;
  m.continuous_force_n = 1.185;
  m.continuous_limit_fraction = 1.0;
  m.depth_mean_m = 2.1e-3;
  m.excursion_m = 1.5e-3;
  classify(m, t, 0.004);
  EXPECT_EQ(m.verdict, Verdict::CannotHold) << m.reason;
  EXPECT_STREQ(verdictName(m.verdict), "cannot-hold");
  m.depth_mean_m = 1.9e-3;  // limited (an oscillation heats the motors), not sunk: judged on its motion
  classify(m, t, 0.004);
  EXPECT_EQ(m.verdict, Verdict::Unstable) << m.reason;
  m.push_force_n = 2.25;  // a push above the continuous force: the limit steps it down, not held
  classify(m, t, 0.004);
  EXPECT_EQ(m.verdict, Verdict::CannotHold) << m.reason;
  m.push_force_n = 1.0;
  m.depth_mean_m = 50e-3;  // sunk, but never limited: not this verdict
  m.continuous_limit_fraction = 0.0;
  classify(m, t, 0.004);
  EXPECT_EQ(m.verdict, Verdict::Unstable) << m.reason;
  // A square of several forces shows the worst verdict among those that test the valley.
  EXPECT_LT(severity(Verdict::CannotHold), severity(Verdict::Stable));
  EXPECT_LT(severity(Verdict::Stable), severity(Verdict::LimitCycle));
  EXPECT_LT(severity(Verdict::LimitCycle), severity(Verdict::Unstable));
}

// Issue 12: at 60 deg and full stiffness, crease+passivity, the pushes above the continuous force
// (1.185 N) held for seconds sink the pen through the floor; the map used to call 4-5 N "stable"
// at 95-127 mm deep and 2.5-3 N "limit-cycle". The same cell at 1 N tests the valley: stable.
TEST(StabilityCells, APushTheDeviceCannotHoldHasItsOwnVerdict) {
  const CellResult held = simulate(cell(60, 1.0, 1.0, true, "crease+passivity"));
  EXPECT_EQ(held.metrics.verdict, Verdict::Stable) << held.metrics.reason;
  for (const double f : {3.0, 5.0}) {
    const CellResult r = simulate(cell(60, 1.0, f, true, "crease+passivity"));
    EXPECT_EQ(r.metrics.verdict, Verdict::CannotHold) << f << " N: " << r.metrics.reason;
    EXPECT_GT(r.metrics.continuous_limit_fraction, 0.5) << f;
    EXPECT_GT(r.metrics.depth_mean_m, 10e-3) << f;       // centimetres through the floor
    EXPECT_LT(r.metrics.normal_force_mean_n, 1.2) << f;  // the continuous force, not the push
  }
}

// ---- hard cases: never a NaN, never beyond the peak ----------------------------------------------

TEST(StabilityHardCases, GrazingNormalsStayFiniteAndBounded) {
  // Walls at 85 deg (the generator's narrowest valley) and a plane tilted 80 deg.
  tex::GenerateRequest tilted;
  tilted.kind = "tilted";
  tilted.size = 128;
  tilted.params = {{"angle_deg", 80.0}, {"extent", 0.02}};
  const tex::TextureMap maps[] = {valleyMap(10.0, 0.04, 200), tex::generate(tilted)};
  for (const tex::TextureMap& map : maps) {
    const double extent = map.meta().extent_x_m;
    for (const bool relief : {true, false}) {
      for (const bool crease : {true, false}) {
        const tex::TexturedSurface surface(map, squareMapping(extent), tex::SampleOptions{}, relief);
        dev::SimPhantomConfig sim = simConfigFor(defaultHand());
        const double x = 0.0015;  // beside a floor / on the slope
        sim.plane_to_world = Eigen::Translation3d(0, 0, surface.at(x, 0).height_m);
        const RunCheck c = run(surface, sim, pressAt(x, 0.0, 2.0, 2.0), rigOptions(crease, true), 2500);
        SCOPED_TRACE(map.meta().kind + (relief ? " relief" : " normal") + (crease ? " crease" : " single"));
        EXPECT_TRUE(c.all_finite);
        EXPECT_EQ(c.nonfinite_commands, 0);
        EXPECT_LE(c.max_force_out_n, kPeakN + 1e-9);
        EXPECT_LE(c.max_motor_n, kPeakN + 1e-9);
        EXPECT_GT(c.contact_ticks, 1500);  // it did press
      }
    }
  }
}

TEST(StabilityHardCases, PressAtTheMapBorderWithClampAddress) {
  const double extent = 0.04;
  const tex::TextureMap map = valleyMap(60.0, extent, 200);
  const tex::SampleOptions clamp{tex::Filter::Bilinear, tex::Address::Clamp};
  // The right edge (a ridge) and the top edge (along the valleys), exactly on the border.
  const Eigen::Vector2d borders[] = {{extent / 2, 0.0}, {0.002, extent / 2}, {extent / 2, extent / 2}};
  for (const Eigen::Vector2d& at : borders) {
    for (const bool crease : {true, false}) {
      const tex::TexturedSurface surface(map, squareMapping(extent), clamp, true);
      dev::SimPhantomConfig sim = simConfigFor(defaultHand());
      sim.plane_to_world = Eigen::Translation3d(0, 0, surface.at(at.x(), at.y()).height_m);
      const RunCheck c = run(surface, sim, pressAt(at.x(), at.y(), 1.0, 2.0), rigOptions(crease, true), 2500);
      SCOPED_TRACE(testing::Message() << "at (" << at.x() << ", " << at.y() << ") crease " << crease);
      EXPECT_TRUE(c.all_finite);
      EXPECT_LE(c.max_force_out_n, kPeakN + 1e-9);
      EXPECT_GT(c.mean_normal_force_n, 0.5);  // the surface still holds the pen up
    }
  }
}

TEST(StabilityHardCases, ProbeOutsideThePlaneRectangle) {
  const double extent = 0.04;
  const tex::TextureMap map = valleyMap(60.0, extent, 200);
  const double floor_x = ValleyGeometry{}.floorXM() + 1e-4;
  for (const tex::Address address : {tex::Address::Wrap, tex::Address::Clamp}) {
    const tex::TexturedSurface surface(map, squareMapping(extent), tex::SampleOptions{tex::Filter::Bilinear, address},
                                       true);
    const auto pressAtX = [&](double x) {
      dev::SimPhantomConfig sim = simConfigFor(defaultHand());
      sim.plane_to_world = Eigen::Translation3d(0, 0, surface.at(x, 0).height_m);
      return run(surface, sim, pressAt(x, 0.0, 1.0, 2.0), rigOptions(true, true), 2500);
    };
    const RunCheck inside = pressAtX(floor_x);
    const RunCheck outside = pressAtX(floor_x + 1.5 * extent);  // one and a half rectangles to the right
    SCOPED_TRACE(address == tex::Address::Wrap ? "wrap" : "clamp");
    EXPECT_TRUE(outside.all_finite);
    EXPECT_LE(outside.max_force_out_n, kPeakN + 1e-9);
    EXPECT_GT(outside.mean_normal_force_n, 0.5);
    if (address == tex::Address::Wrap) {
      // The tiling map repeats: 1.5 rectangles = 15 whole periods away is the same valley floor.
      EXPECT_NEAR(outside.mean_normal_force_n, inside.mean_normal_force_n, 0.02);
    }
  }
}

TEST(StabilityHardCases, StrokeAtTwoMetresPerSecondAcrossManyValleys) {
  const double extent = 0.04;
  const tex::TextureMap map = valleyMap(60.0, extent, 200);
  for (const bool relief : {true, false}) {
    for (const bool crease : {true, false}) {
      const tex::TexturedSurface surface(map, squareMapping(extent), tex::SampleOptions{}, relief);
      // 0.1 m at 2 m/s: 25 valleys (the map wraps), 50 ms of stroke plus its speed ramps.
      const dev::HandScript script(
          {dev::HandHold{0.5}, dev::HandStroke{{-0.05, 0.0}, {0.05, 0.0}, 2.0, 1.0}, dev::HandHold{0.2}});
      const long ticks = std::lround(script.duration() * 1000);
      const RunCheck c = run(surface, simConfigFor(defaultHand()), script, rigOptions(crease, true), ticks);
      SCOPED_TRACE(std::string(relief ? "relief" : "normal") + (crease ? " crease" : " single"));
      EXPECT_TRUE(c.all_finite);
      EXPECT_EQ(c.nonfinite_commands, 0);
      EXPECT_LE(c.max_force_out_n, kPeakN + 1e-9);
      EXPECT_LE(c.max_motor_n, kPeakN + 1e-9);
      EXPECT_GT(c.contact_ticks, 50);  // in contact through the 2 m/s part
    }
  }
}

// ---- faults -------------------------------------------------------------------------------------

TEST(StabilityHardCases, NonFiniteReadingsZeroTheForceAndDisengage) {
  const ValleyGeometry g;
  const tex::TextureMap map = valleyMap(60.0, g.extentM(), g.sizeTexels());
  const tex::TexturedSurface surface(map, squareMapping(g.extentM()), tex::SampleOptions{}, true);
  const double x = g.floorXM() + 1e-4;
  dev::SimPhantomConfig sim = simConfigFor(defaultHand());
  sim.plane_to_world = Eigen::Translation3d(0, 0, surface.at(x, 0).height_m);
  sim.faults.nan_from_tick = 2000;  // pressing with ~1 N by then
  sim.faults.nan_ticks = 5;
  SimRig rig(surface, sim, pressAt(x, 0.0, 1.0, 3.0), rigOptions(true, true));

  long first_nan = -1;
  for (long k = 0; k < 2200; ++k) {
    const srv::TickRecord& r = rig.tick();
    const Eigen::Vector3d f(r.f_out[0], r.f_out[1], r.f_out[2]);
    ASSERT_TRUE(f.allFinite()) << "tick " << r.tick;
    if (r.tick < 2000) {
      if (r.tick >= 1900) {
        ASSERT_GT(f.norm(), 0.5) << "tick " << r.tick;  // holding the press
      }
      continue;
    }
    if (first_nan < 0) first_nan = r.tick;
    if (r.tick < 2000 + 5) {
      EXPECT_FALSE(r.valid);
      EXPECT_EQ(f.norm(), 0.0) << "tick " << r.tick;  // nothing to render from: zero at once
    } else {
      // Readings are fine again but the pen still presses: the safety stage stays disengaged
      // until the request is small, so the force stays off.
      EXPECT_EQ(f.norm(), 0.0) << "tick " << r.tick;
    }
  }
  EXPECT_EQ(first_nan, 2000);
  EXPECT_EQ(rig.safety().state(), srv::SafetyState::Disengaged);
  EXPECT_GE(rig.safety().counters().disengage_events, 1u);
  // One fault for the episode (at the third invalid reading in a row), not one per tick.
  EXPECT_EQ(rig.servo().counters().faults, 1u);
  EXPECT_EQ(rig.truth().nonfinite_commands, 0);   // the device never saw a NaN
}

// ---- a renderer bug the map exposed (docs/stability.md, "Bugs found") ---------------------------

// Bug A of docs/stability.md (fixed): applyRecovery() used to re-arm the recovery ramp on every
// tick whose target penetration moved by more than 0.2 mm, so a tip entering a wall faster than
// 0.2 m/s kept the PREVIOUS tick's penetration for as long as it kept moving: the spring froze and
// a firm press popped through. A plain wall (no plane change at all) renders K x depth whatever
// the approach speed.
TEST(RendererRecovery, FastPressIntoAFlatWallIsNotFrozen) {
  tex::GenerateRequest g;
  g.kind = "tilted";
  g.size = 64;
  g.params = {{"angle_deg", 0.0}, {"extent", 0.01}};
  const tex::TextureMap map = tex::generate(g);
  const tex::TexturedSurface surface(map, squareMapping(0.01), tex::SampleOptions{}, false);
  for (const bool crease : {false, true}) {
    srv::RendererConfig rc;
    rc.stiffness_n_per_m = 1000.0;
    rc.crease_handling = crease;
    srv::ProxyRenderer renderer(surface, rc);
    const double speed_m_per_s = 0.25;  // a tap, not an impact
    double z = 0.0;
    srv::RenderOutput out;
    for (int k = 0; k < 20; ++k) {
      z -= speed_m_per_s * 1e-3;
      out = renderer.render({0.001, 0.0, z}, {0.0, 0.0, -speed_m_per_s});
    }
    // 5 mm deep: 5 N. Today: 0.25 N (the first tick's 0.25 mm), recovering on every tick.
    EXPECT_NEAR(out.force_world.z(), 1000.0 * -z, 0.5) << "crease " << crease;
    EXPECT_FALSE(out.recovering);
  }
}

// ---- configuration ------------------------------------------------------------------------------

TEST(StabilityBudgetAtMapStiffness, FullStiffnessIsBeyondTheBoundAndStrictRefusesIt) {
  srv::StabilityRequest r;
  r.stiffness_fraction = 1.0;
  r.virtual_damping_ns_per_m = CellSetup{}.virtual_damping_ns_per_m;
  r.period_s = 1e-3;
  r.policy = srv::BoundPolicy::Warn;
  const srv::StabilityBudget warn = srv::checkStabilityBudget(dev::phantomDesktopSpec(), r);
  EXPECT_FALSE(warn.within_bound);
  EXPECT_TRUE(warn.ok);
  EXPECT_FALSE(warn.message.empty());
  EXPECT_GT(warn.required_physical_damping_ns_per_m, 0.5);  // K T / 2 + |B| = 1.5 N s/m
  r.policy = srv::BoundPolicy::Strict;
  const srv::StabilityBudget strict = srv::checkStabilityBudget(dev::phantomDesktopSpec(), r);
  EXPECT_FALSE(strict.ok);
  EXPECT_FALSE(strict.errors.empty());
}

TEST(StabilityCells, MismatchedValleyMapIsRefused) {
  const ValleyMap v = buildValleyMap(40.0, false, ValleyGeometry{});
  EXPECT_THROW(simulateCell(cell(60, 1.0, 1.0, true, "none"), v, CellSetup{}), thx::Error);
  EXPECT_THROW(simulateCell(cell(40, 1.0, 1.0, true, "smoothing"), v, CellSetup{}), thx::Error);
}

}  // namespace test_stability_cells
