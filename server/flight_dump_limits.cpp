#include "server/flight_dump_limits.hpp"

#include <cmath>

#include "base/error.hpp"
#include "base/number_text.hpp"

namespace thx::srv {

FlightDumpGate::FlightDumpGate(const FlightDumpLimits& limits, double period_s) : limits_(limits), period_s_(period_s) {
  if (!std::isfinite(limits.min_interval_s) || limits.min_interval_s < 0.0) {
    throw thx::Error(thx::Error::Kind::Config, "flight records: min_interval_s = " + numberText(limits.min_interval_s) +
                                                   ": expected a finite interval >= 0 s");
  }
  if (!std::isfinite(period_s) || period_s <= 0.0) {
    throw thx::Error(thx::Error::Kind::Config,
                     "flight records: period_s = " + numberText(period_s) + ": expected a finite servo period > 0 s");
  }
}

FlightDumpOutcome FlightDumpGate::admit(std::int64_t tick) {
  if (written_ >= limits_.max_files) {
    ++over_count_;
    return FlightDumpOutcome::OverCount;
  }
  if (any_written_ && double(tick - last_written_tick_) * period_s_ < limits_.min_interval_s) {
    ++over_rate_;
    return FlightDumpOutcome::OverRate;
  }
  any_written_ = true;
  last_written_tick_ = tick;
  ++written_;
  return FlightDumpOutcome::Written;
}

FlightDump dumpWithinLimits(FlightRecorder& recorder, FlightDumpGate& gate, const std::string& directory,
                            const std::string& tag) {
  FlightDump d;
  const std::optional<std::int64_t> tick = recorder.pendingTick();
  if (!tick) return d;
  d.outcome = gate.admit(*tick);
  if (d.outcome == FlightDumpOutcome::Written) {
    d.path = recorder.dumpPending(directory, tag);
  } else {
    recorder.discardPending();
  }
  return d;
}

}  // namespace thx::srv
