#include "server/servo_group.hpp"

#include <string>

#include "base/error.hpp"

namespace thx::srv {

ServoGroup::ServoGroup(rt::Clock& clock, std::int64_t period_ns, std::int64_t spin_ns)
    : pacer_(clock, period_ns, spin_ns) {}

void ServoGroup::add(Servo& servo, const char* name) {
  const std::string who = std::string("device ") + std::to_string(size_) + (*name ? std::string(" '") + name + "'" : "");
  if (size_ >= kMaxDevices)
    throw Error(Error::Kind::Config, who + ": one servo clock serves at most " + std::to_string(kMaxDevices) +
                                         " devices");
  for (int i = 0; i < size_; ++i)
    if (members_[std::size_t(i)] == &servo) throw Error(Error::Kind::Config, who + ": this servo is in the group already");
  if (!servo.device().sharesClock())
    throw Error(Error::Kind::Config, who + ": its device paces itself and cannot be read at another clock's tick");
  members_[std::size_t(size_++)] = &servo;
}

const ServoGroup::Tick& ServoGroup::tick() {
  tick_.timing = pacer_.wait();
  const std::int64_t t0 = rt::monotonicNowNs();  // real CPU time even on a virtual clock
  for (int i = 0; i < size_; ++i) members_[std::size_t(i)]->tickAt(tick_.timing);
  tick_.compute_ns = rt::monotonicNowNs() - t0;
  compute_hist_.add(tick_.compute_ns);
  wake_hist_.add(tick_.timing.wake_latency_ns);
  return tick_;
}

void ServoGroup::requestShutdown() {
  for (int i = 0; i < size_; ++i) members_[std::size_t(i)]->requestShutdown();
}

bool ServoGroup::finished() const {
  for (int i = 0; i < size_; ++i)
    if (!members_[std::size_t(i)]->finished()) return false;
  return true;
}

}  // namespace thx::srv
