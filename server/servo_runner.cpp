#include "server/servo_runner.hpp"

#include <chrono>
#include <cmath>
#include <exception>

namespace thx::srv {

std::int64_t stopTickAfter(double duration_s, double rate_hz) {
  return duration_s > 0 ? std::int64_t(std::llround(duration_s * rate_hz)) : -1;
}

ServoRunner::ServoRunner(Servo& servo, const rt::SpscRing<TickRecord>& ring, const ServoRunnerOptions& options)
    : servo_(servo), ring_(ring), options_(options) {}

ServoRunner::~ServoRunner() { join(); }

ServoRunner::Step ServoRunner::step() {
  if (servo_.finished()) return Step::Finished;
  if (options_.lockstep && ring_.size() + 2 >= ring_.capacity()) return Step::WaitingForReader;
  const TickRecord& r = servo_.tick();
  const std::int64_t n = ticks_.load(std::memory_order_relaxed);
  if (n == 0) first_deadline_ns_ = r.deadline_ns;
  last_deadline_ns_ = r.deadline_ns;
  ticks_.store(n + 1, std::memory_order_relaxed);
  const bool stop = stop_requested_.load(std::memory_order_relaxed) ||
                    (options_.stop_flag && options_.stop_flag->load(std::memory_order_relaxed)) ||
                    (options_.stop_tick >= 0 && r.tick >= options_.stop_tick);
  if (!shutting_down_ && stop) {
    servo_.requestShutdown();
    shutting_down_ = true;
  }
  return Step::Ticked;
}

void ServoRunner::run() {
  for (Step s = step(); s != Step::Finished; s = step()) {
    if (s == Step::WaitingForReader) std::this_thread::sleep_for(std::chrono::microseconds(100));
  }
}

void ServoRunner::start(dev::HapticDevice& device, const RealtimeOptions& rt) {
  thread_ = std::thread([this, &device, rt] {
    try {
      realtime_ = makeThreadRealtime(rt);
    } catch (const std::exception& e) {
      error_ = e.what();
      done_.store(true);
      return;
    }
    try {
      device.open();
    } catch (const std::exception& e) {
      error_ = std::string("cannot open the device: ") + e.what();
      done_.store(true);
      return;
    }
    run();
    done_.store(true);
  });
}

void ServoRunner::join() {
  if (thread_.joinable()) thread_.join();
}

}  // namespace thx::srv
