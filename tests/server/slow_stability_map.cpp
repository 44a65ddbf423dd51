// The stability map's headline at full device stiffness (docs/stability.md), over every opening
// angle, push force and representation of the documented map: without mitigations steep valleys
// are unstable; with crease handling (alone or with the passivity controller) no cell is. Label
// `slow` (ctest -L slow): 192 cells, a second optimised, much longer under the sanitizers.
#include <gtest/gtest.h>

#include "server/tools/stability_map_sweep.hpp"

namespace slow_stability_map {

using namespace thx::srv::stab;

namespace {

std::vector<CellResult> fullStiffnessRow(const char* mitigations) {
  SweepAxes axes = fullAxes();
  axes.stiffness_fractions = {1.0};
  axes.mitigations.clear();
  const std::string m = mitigations;
  axes.mitigations.push_back(Mitigations{m.find("crease") != std::string::npos,
                                         m.find("passivity") != std::string::npos, false});
  return runSweep(enumerateCells(axes), CellSetup{}, 2);
}

}  // namespace

TEST(StabilityMapSlow, WithoutMitigationsSteepValleysAreUnstableAtFullStiffness) {
  // Of the cells that test the valley: at 1 N, 20 deg (both readings) and 40 deg relief sink
  // while the continuous-force limit acts (cannot-hold: they do not test it; docs/stability.md).
  int tested = 0;
  for (const CellResult& r : fullStiffnessRow("none")) {
    if (r.params.angle_deg > 60 || r.params.push_force_n != 1.0) continue;
    if (r.metrics.verdict == Verdict::CannotHold) continue;
    ++tested;
    EXPECT_EQ(r.metrics.verdict, Verdict::Unstable)
        << r.params.angle_deg << " deg " << (r.params.relief ? "relief" : "normal") << ": " << r.metrics.reason;
  }
  EXPECT_GE(tested, 3);
}

TEST(StabilityMapSlow, CreaseHandlingLeavesNoUnstableCellAtFullStiffness) {
  for (const char* m : {"crease", "crease+passivity"}) {
    for (const CellResult& r : fullStiffnessRow(m)) {
      EXPECT_NE(r.metrics.verdict, Verdict::Unstable)
          << m << ": " << r.params.angle_deg << " deg " << r.params.push_force_n << " N "
          << (r.params.relief ? "relief" : "normal") << ": " << r.metrics.reason;
    }
  }
}

}  // namespace slow_stability_map
