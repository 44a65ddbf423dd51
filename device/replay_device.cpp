#include "device/replay_device.hpp"

#include <string>
#include <utility>

namespace thx::dev {

namespace {

// The sample's pose and buttons; its velocities only while it is moving (a held or finished pen
// is at rest).
void show(DeviceState& s, const ReplaySample& m, bool moving, bool valid) {
  s.p_world = m.p_world;
  s.q_world = m.q_world;
  s.v_world = moving ? m.v_world : Eigen::Vector3d::Zero();
  s.w_world = moving ? m.w_world : Eigen::Vector3d::Zero();
  s.buttons = m.buttons;
  s.valid = valid;
}

}  // namespace

ReplayDevice::ReplayDevice(std::vector<ReplaySample> samples, DeviceSpec spec, ReplayOptions options)
    : samples_(std::move(samples)),
      spec_(std::move(spec)),
      options_(options),
      pacer_(monotonic_, options.period_ns) {
  if (samples_.empty()) throw DeviceError("replay: the recording holds no device samples");
  if (options_.period_ns <= 0) throw DeviceError("replay: the period must be > 0");
  for (std::size_t i = 1; i < samples_.size(); ++i) {
    if (samples_[i].tick <= samples_[i - 1].tick)
      throw DeviceError("replay: sample " + std::to_string(i) + " has tick " + std::to_string(samples_[i].tick) +
                        " after tick " + std::to_string(samples_[i - 1].tick) + "; expected increasing ticks");
  }
}

void ReplayDevice::open() {
  next_ = 0;
  group_started_ = false;
  if (!options_.lockstep) pacer_.start();
}

double ReplayDevice::durationS() const {
  return double(samples_.back().tick - samples_.front().tick + 1) * double(options_.period_ns) * 1e-9;
}

DeviceState ReplayDevice::read() {
  DeviceState s;
  if (options_.lockstep) {
    std::int64_t tick = 0;
    if (next_ < samples_.size()) {
      tick = samples_[next_].tick;
      s.timing.missed = next_ == 0 ? 0 : tick - samples_[next_ - 1].tick - 1;
    } else {
      tick = samples_.back().tick + std::int64_t(next_ - samples_.size() + 1);  // after the end
    }
    s.timing.tick = tick;
    s.timing.deadline_ns = tick * options_.period_ns;
    virtual_.sleepUntilNs(s.timing.deadline_ns);
    s.timing.wake_ns = virtual_.nowNs();
    s.timing.wake_latency_ns = s.timing.wake_ns - s.timing.deadline_ns;
  } else {
    s.timing = pacer_.wait();
    if (s.timing.missed > 0) next_ += std::size_t(s.timing.missed);  // keep wall-clock time
  }
  const bool have = next_ < samples_.size();
  show(s, have ? samples_[next_] : samples_.back(), have, have);
  ++next_;
  return s;
}

DeviceState ReplayDevice::readTick(const rt::TickTiming& timing) {
  DeviceState s;
  s.timing = timing;
  if (!group_started_) {
    tick_offset_ = samples_.front().tick - timing.tick;
    group_started_ = true;
  }
  const std::int64_t recorded = timing.tick + tick_offset_;
  while (next_ < samples_.size() && samples_[next_].tick < recorded) ++next_;  // the group missed periods
  const bool have = next_ < samples_.size();
  const bool recorded_here = have && samples_[next_].tick == recorded;
  // A tick the recording lacks holds the sample before it (the first one before any).
  show(s, !have ? samples_.back() : recorded_here || next_ == 0 ? samples_[next_] : samples_[next_ - 1], recorded_here,
       have);
  if (recorded_here) ++next_;
  return s;
}

void ReplayDevice::write(const DeviceCommand&) { ++writes_; }

}  // namespace thx::dev
