// The pen with extent in the stability map (issue 30; stability-map --tool): a capsule held by the
// virtual coupling, upright with its tip's ball in a steep V-valley or lying level across the
// ridges, at full stiffness with no mitigation, where the point pen without crease handling is
// thrown out of the valley (test_stability_cells.cpp). Lock-step and deterministic.
#include <gtest/gtest.h>

#include <string>

#include "server/tools/stability_map_cell.hpp"
#include "tests/support/error_text.hpp"

namespace test_stability_capsule_cells {

using namespace thx;
using namespace thx::srv::stab;

namespace {

CellParams steepCell(bool passivity) {
  CellParams p;
  p.angle_deg = 60.0;
  p.stiffness_fraction = 1.0;
  p.push_force_n = 1.0;
  p.relief = true;
  p.mitigations.passivity = passivity;
  return p;
}

CellResult simulate(const CellParams& p, PenTool tool) {
  CellSetup setup;
  setup.tool = tool;
  const ValleyMap valley = buildValleyMap(p.angle_deg, p.mitigations.smoothing, setup.geometry);
  return simulateCell(p, valley, setup);
}

}  // namespace

TEST(StabilityCapsuleCells, ACapsuleRestsInTheSteepValleyThePointPenLeaves) {
  CellParams point = steepCell(false);
  EXPECT_EQ(simulate(point, PenTool::Point).metrics.verdict, Verdict::Unstable);
  // Lying across the ridges the tool touches every crest under it, the costliest cell here (slower
  // still under the sanitizers): that pose without the controller only, the harder case.
  for (const PenTool tool : {PenTool::Capsule, PenTool::CapsuleAcross}) {
    for (const bool passivity : {false, true}) {
      if (tool == PenTool::CapsuleAcross && passivity) continue;
      const CellResult r = simulate(steepCell(passivity), tool);
      EXPECT_EQ(r.metrics.verdict, Verdict::Stable) << penToolName(tool) << ": " << r.metrics.reason;
      EXPECT_LT(r.metrics.lateral_pp_m, 2 * 2.3e-5) << penToolName(tool);  // within two encoder counts
      EXPECT_LT(r.metrics.excursion_m, 1e-3) << penToolName(tool);        // in its valley
      // The surface carries the push (and the hand's spring, which pulls towards the floor the
      // ball rests above).
      EXPECT_GT(r.metrics.normal_force_mean_n, 0.9) << penToolName(tool);
      EXPECT_LT(r.metrics.normal_force_mean_n, 1.5) << penToolName(tool);
      EXPECT_TRUE(r.metrics.finite);
    }
  }
}

TEST(StabilityCapsuleCells, ACapsuleTakesOnlyWhatItCanBeRenderedWith) {
  CellParams crease = steepCell(true);
  crease.mitigations.crease = true;
  EXPECT_NE(test::errorOf([&] { simulate(crease, PenTool::Capsule); }).find("a capsule takes none, passivity and smoothing"),
            std::string::npos);
  CellParams normal = steepCell(true);
  normal.relief = false;
  EXPECT_NE(test::errorOf([&] { simulate(normal, PenTool::CapsuleAcross); }).find("needs the relief"), std::string::npos);
}

}  // namespace test_stability_capsule_cells
