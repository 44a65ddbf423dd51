#pragma once
// The per-block mode budget (docs/audio.md, "Live audio"): how many modes the callback may
// synthesise, lowered when it runs late and raised again slowly when it has room, so that load
// costs quality instead of a glitch. The caller measures the callback's cost per block (a clock
// read at its start and end) and says whether the block started late; the policy is a pure
// function of those numbers, so a fake clock tests it exactly.
//
//   load = cost / period. load > shed_above, or a late block: budget *= target / load (target =
//   shed_above * shed_margin), at least one mode less (a late block with a low load: 3/4).
//   load < grow_below for grow_after blocks in a row: budget += max(1, grow_step * max).
// The budget stays in [min_modes, max_modes]. The synthesis drops the modes beyond the budget
// from the end of its list: the highest (the modes are sorted by frequency), which also decay the
// fastest (Rayleigh damping: d = (alpha + beta omega^2) / 2 grows with the frequency).
#include <cstddef>
#include <cstdint>

namespace thx::audio {

struct ModeBudgetOptions {
  double shed_above = 0.5;    // of the block period
  double shed_margin = 0.8;   // shed to this fraction of shed_above
  double grow_below = 0.25;   // of the block period
  int grow_after = 16;        // consecutive light blocks before growing
  double grow_step = 0.125;   // of max_modes
  std::size_t min_modes = 1;
};

class ModeBudget {
 public:
  ModeBudget(std::size_t max_modes, ModeBudgetOptions options = {});

  // One block: its measured cost and period (ns), and whether it started late. Returns the budget
  // for the next block.
  std::size_t update(std::int64_t cost_ns, std::int64_t period_ns, bool late);

  std::size_t current() const { return current_; }
  std::size_t maxModes() const { return max_; }
  // A new scene: a new maximum, and the budget back at it.
  void reset(std::size_t max_modes);
  std::uint64_t sheds() const { return sheds_; }
  std::uint64_t grows() const { return grows_; }

 private:
  ModeBudgetOptions o_;
  std::size_t max_ = 0, current_ = 0;
  int light_blocks_ = 0;
  std::uint64_t sheds_ = 0, grows_ = 0;
};

}  // namespace thx::audio
