#include "clients/audio/live/mode_budget.hpp"

#include <algorithm>
#include <cmath>

namespace thx::audio {

ModeBudget::ModeBudget(std::size_t max_modes, ModeBudgetOptions options) : o_(options) { reset(max_modes); }

void ModeBudget::reset(std::size_t max_modes) {
  max_ = max_modes;
  current_ = max_modes;
  light_blocks_ = 0;
}

std::size_t ModeBudget::update(std::int64_t cost_ns, std::int64_t period_ns, bool late) {
  const std::size_t floor_modes = std::min(o_.min_modes, max_);
  const double load = period_ns > 0 ? double(cost_ns) / double(period_ns) : 0.0;
  if (load > o_.shed_above || late) {
    light_blocks_ = 0;
    std::size_t next = current_;
    if (load > o_.shed_above) {
      next = std::size_t(std::floor(double(current_) * o_.shed_above * o_.shed_margin / load));
      next = std::min(next, current_ > 0 ? current_ - 1 : 0);
    } else {
      next = current_ * 3 / 4;  // late although cheap: someone else took the time; yield some
    }
    next = std::max(next, floor_modes);
    if (next < current_) ++sheds_;
    current_ = next;
    return current_;
  }
  if (load < o_.grow_below && current_ < max_) {
    if (++light_blocks_ >= o_.grow_after) {
      light_blocks_ = 0;
      const std::size_t step = std::max<std::size_t>(1, std::size_t(o_.grow_step * double(max_)));
      current_ = std::min(max_, current_ + step);
      ++grows_;
    }
  } else {
    light_blocks_ = 0;
  }
  return current_;
}

}  // namespace thx::audio
