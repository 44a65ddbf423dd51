#include "rt/clock.hpp"

#include <cerrno>
#include <ctime>

namespace thx::rt {

std::int64_t MonotonicClock::nowNs() { return monotonicNowNs(); }

void MonotonicClock::sleepUntilNs(std::int64_t t_ns) {
  timespec ts{};
  ts.tv_sec = time_t(t_ns / 1'000'000'000);
  ts.tv_nsec = long(t_ns % 1'000'000'000);
  // A signal (SIGINT for shutdown) interrupts the sleep; resume towards the same absolute deadline.
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

void MonotonicClock::spinUntilNs(std::int64_t t_ns) {
  while (monotonicNowNs() < t_ns) {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();  // tells the core (and a hypervisor) that this is a spin
#endif
  }
}

}  // namespace thx::rt
