#pragma once
// The sweep: every combination of the axes, simulated on a pool of threads. Each cell is an
// independent lock-step simulation and results are stored by cell index, so the output does not
// depend on the number of threads or on scheduling.
#include <cstddef>
#include <functional>
#include <vector>

#include "server/tools/stability_map_cell.hpp"

namespace thx::srv::stab {

struct SweepAxes {
  std::vector<double> angles_deg;
  std::vector<double> stiffness_fractions;
  std::vector<double> push_forces_n;
  std::vector<bool> relief;  // false = normal map, true = relief map
  std::vector<Mitigations> mitigations;
};

SweepAxes fullAxes();   // the documented map (docs/stability.md)
SweepAxes quickAxes();  // a small subset for CI: both verdicts, a few seconds

// Cell order: mitigations, representation, angle, stiffness, push force (the last varies fastest).
std::vector<CellParams> enumerateCells(const SweepAxes& axes);

// Called from the worker threads, serialised, after each cell: (cells done, total).
using ProgressFn = std::function<void(std::size_t done, std::size_t total)>;

// Builds each (angle, smoothing) map once, then simulates every cell. threads >= 1.
std::vector<CellResult> runSweep(const std::vector<CellParams>& cells, const CellSetup& setup, int threads,
                                 const ProgressFn& progress = {});

}  // namespace thx::srv::stab
