#include "server/tools/stability_map_sweep.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>

namespace thx::srv::stab {

namespace {

// The paper's loop first (the baseline), then its mitigation, then this server's eight.
std::vector<Mitigations> allMitigations() {
  std::vector<Mitigations> m = {Mitigations::fromIndex(8), Mitigations::fromIndex(8 | 4)};
  for (int i = 0; i < 8; ++i) m.push_back(Mitigations::fromIndex(i));
  return m;
}

}  // namespace

SweepAxes fullAxes() {
  return SweepAxes{{20, 40, 60, 80, 100, 120, 140, 160}, {0.1, 0.25, 0.5, 0.75, 1.0},
                   {0.5, 1, 1.5, 2, 2.25, 2.5, 3, 5},  // 1.5-3 N: where the continuous-force budget starts to bind
                   {false, true}, allMitigations()};
}

SweepAxes quickAxes() {
  return SweepAxes{{20, 60, 120}, {0.25, 1.0}, {1.0}, {false, true},
                   {Mitigations::fromIndex(8), Mitigations::fromIndex(0), Mitigations::fromIndex(3),
                    Mitigations::fromIndex(7)}};
}

std::vector<CellParams> enumerateCells(const SweepAxes& a) {
  std::vector<CellParams> cells;
  for (const Mitigations& m : a.mitigations)
    for (const bool relief : a.relief)
      for (const double angle : a.angles_deg)
        for (const double k : a.stiffness_fractions)
          for (const double f : a.push_forces_n) cells.push_back(CellParams{angle, k, f, relief, m});
  return cells;
}

std::vector<CellResult> runSweep(const std::vector<CellParams>& cells, const CellSetup& setup, int threads,
                                 const ProgressFn& progress) {
  if (threads < 1) throw std::logic_error("runSweep: threads must be >= 1");
  // Maps first, on this thread: a few hundred texels square each, shared read-only afterwards.
  std::map<std::pair<double, bool>, ValleyMap> maps;
  for (const CellParams& c : cells) {
    const auto key = std::make_pair(c.angle_deg, c.mitigations.smoothing);
    if (!maps.count(key)) maps.emplace(key, buildValleyMap(c.angle_deg, c.mitigations.smoothing, setup.geometry));
  }

  std::vector<CellResult> results(cells.size());
  std::atomic<std::size_t> next{0};
  std::size_t done = 0;
  std::mutex mutex;  // progress and the first error
  std::exception_ptr error;
  const auto work = [&] {
    for (;;) {
      const std::size_t i = next.fetch_add(1);
      if (i >= cells.size()) return;
      try {
        const ValleyMap& valley = maps.at({cells[i].angle_deg, cells[i].mitigations.smoothing});
        results[i] = simulateCell(cells[i], valley, setup);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        next.store(cells.size());  // stop handing out work
        return;
      }
      const std::lock_guard<std::mutex> lock(mutex);
      ++done;
      if (progress) progress(done, cells.size());
    }
  };
  std::vector<std::thread> pool;
  const std::size_t n = std::min<std::size_t>(std::size_t(threads), std::max<std::size_t>(1, cells.size()));
  for (std::size_t t = 1; t < n; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  return results;
}

}  // namespace thx::srv::stab
