#include "server/servo_runner.hpp"

#include <chrono>
#include <cmath>
#include <exception>

namespace thx::srv {

std::int64_t stopTickAfter(double duration_s, double rate_hz) {
  return duration_s > 0 ? std::int64_t(std::llround(duration_s * rate_hz)) : -1;
}

ServoRunner::ServoRunner(Servo& servo, const rt::SpscRing<TickRecord>& ring, const ServoRunnerOptions& options)
    : servo_(&servo), ring_(&ring), options_(options) {}

ServoRunner::ServoRunner(ServoGroup& group, const ServoRunnerOptions& options) : group_(&group), options_(options) {}

bool ServoRunner::readerBehind() const {
  const auto behind = [](const rt::SpscRing<TickRecord>& ring) { return ring.size() + 2 >= ring.capacity(); };
  if (!group_) return behind(*ring_);
  for (int i = 0; i < group_->size(); ++i)
    if (behind(group_->member(i).ring())) return true;
  return false;
}

ServoRunner::~ServoRunner() { join(); }

ServoRunner::Step ServoRunner::step() {
  if (finished()) return Step::Finished;
  if (options_.lockstep && readerBehind()) return Step::WaitingForReader;
  std::int64_t tick = 0, deadline_ns = 0;
  if (group_) {
    const rt::TickTiming& t = group_->tick().timing;
    tick = t.tick;
    deadline_ns = t.deadline_ns;
  } else {
    const TickRecord& r = servo_->tick();
    tick = r.tick;
    deadline_ns = r.deadline_ns;
  }
  const std::int64_t n = ticks_.load(std::memory_order_relaxed);
  if (n == 0) first_deadline_ns_ = deadline_ns;
  last_deadline_ns_ = deadline_ns;
  ticks_.store(n + 1, std::memory_order_relaxed);
  const bool stop = stop_requested_.load(std::memory_order_relaxed) ||
                    (options_.stop_flag && options_.stop_flag->load(std::memory_order_relaxed)) ||
                    (options_.stop_tick >= 0 && tick >= options_.stop_tick);
  if (!shutting_down_ && stop) {
    if (group_)
      group_->requestShutdown();
    else
      servo_->requestShutdown();
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
  thread_ = std::thread([this, &device, rt] { openAndRun(rt, &device); });
}

void ServoRunner::start(const RealtimeOptions& rt) {
  thread_ = std::thread([this, rt] { openAndRun(rt, nullptr); });
}

void ServoRunner::openAndRun(const RealtimeOptions& rt, dev::HapticDevice* device) {
  try {
    realtime_ = makeThreadRealtime(rt);
  } catch (const std::exception& e) {
    error_ = e.what();
    done_.store(true);
    return;
  }
  int opening = 0;
  try {
    if (device) {
      device->open();
    } else if (group_) {
      for (; opening < group_->size(); ++opening) group_->member(opening).device().open();
      group_->start();
    } else {
      servo_->device().open();
    }
  } catch (const std::exception& e) {
    error_ = (group_ ? "cannot open device " + std::to_string(opening) + ": " : std::string("cannot open the device: ")) +
             e.what();
    if (group_)
      for (int i = 0; i < opening; ++i) group_->member(i).device().close();
    done_.store(true);
    return;
  }
  run();
  done_.store(true);
}

void ServoRunner::join() {
  if (thread_.joinable()) thread_.join();
}

}  // namespace thx::srv
