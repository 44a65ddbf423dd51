#pragma once
// Time sources for the servo. The device is the clock: a real device paces the loop with its own
// ticks; the simulated device paces it with MonotonicClock (real time) or VirtualClock (lock-step,
// for deterministic tests: sleeping just advances virtual time).
#include <time.h>

#include <cstdint>

namespace thx::rt {

// CLOCK_MONOTONIC in ns through the vDSO (no system call): for timestamps and measurements in
// any thread, the servo's included.
inline std::int64_t monotonicNowNs() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return std::int64_t(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

class Clock {
 public:
  virtual ~Clock() = default;
  virtual std::int64_t nowNs() = 0;
  // Returns when nowNs() >= t_ns. Real-time safe: no allocation, no locks.
  virtual void sleepUntilNs(std::int64_t t_ns) = 0;
  // The same, without giving up the CPU (a busy wait on the clock): the Pacer's last stretch
  // before a deadline when asked to spin. By default it sleeps.
  virtual void spinUntilNs(std::int64_t t_ns) { sleepUntilNs(t_ns); }
};

// CLOCK_MONOTONIC with clock_nanosleep(TIMER_ABSTIME): absolute deadlines never drift.
class MonotonicClock final : public Clock {
 public:
  std::int64_t nowNs() override;
  void sleepUntilNs(std::int64_t t_ns) override;
  void spinUntilNs(std::int64_t t_ns) override;
};

// Lock-step time: sleepUntilNs jumps to the deadline; advance() models compute time in tests.
class VirtualClock final : public Clock {
 public:
  explicit VirtualClock(std::int64_t start_ns = 0) : now_ns_(start_ns) {}
  std::int64_t nowNs() override { return now_ns_; }
  void sleepUntilNs(std::int64_t t_ns) override {
    if (t_ns > now_ns_) now_ns_ = t_ns;
  }
  void advance(std::int64_t dt_ns) { now_ns_ += dt_ns; }

 private:
  std::int64_t now_ns_;
};

}  // namespace thx::rt
