#pragma once
// ReplayDevice: plays a recorded pen trajectory back as a HapticDevice, so a recorded session can
// be rendered again with other settings (`hapticd --device replay:FILE`, docs/clients.md). The
// pen is kinematic: it goes where the recording went, whatever force the servo writes (the
// writes are counted, not applied).
//
// Timing:
//  - lock-step (options.lockstep): sample i is returned at the i-th read() with the RECORDED tick
//    index, the recorded gap before it as the missed-tick count, and the deadline tick x period
//    on a virtual clock. The servo therefore sees exactly the tick sequence it saw when
//    recording: replay is deterministic and reproduces the missed-tick policy too.
//  - real time: read() paces on the period (Pacer on the monotonic clock); a tick the replay
//    misses skips that many samples, so the trajectory keeps wall-clock time.
//  - under another clock (several devices' group, server/servo_group.hpp; readTick()): the group's
//    first tick plays the first sample, and group tick t the sample recorded t ticks after it. A
//    tick the recording lacks (a missed tick while recording: every device of a group missed it
//    alike) holds the last sample, valid: the group's clock cannot miss it again. A group's
//    missed periods skip samples, as in real time.
// After the last sample read() keeps returning it with valid = false and finished() is true.
// Nothing allocates after the constructor.
#include <cstdint>
#include <vector>

#include "rt/clock.hpp"
#include "device/haptic_device.hpp"
#include "rt/pacer.hpp"

namespace thx::dev {

struct ReplaySample {
  std::int64_t tick = 0;  // the recorded tick index (increasing; gaps are missed ticks)
  Eigen::Vector3d p_world = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_world = Eigen::Quaterniond::Identity();
  Eigen::Vector3d v_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_world = Eigen::Vector3d::Zero();
  std::uint32_t buttons = 0;
};

struct ReplayOptions {
  std::int64_t period_ns = 1'000'000;
  bool lockstep = false;
};

class ReplayDevice final : public HapticDevice {
 public:
  // `samples` must be non-empty with strictly increasing ticks (throws DeviceError otherwise).
  ReplayDevice(std::vector<ReplaySample> samples, DeviceSpec spec, ReplayOptions options);

  const DeviceSpec& spec() const override { return spec_; }
  OutputMode outputMode() const override { return OutputMode::Force; }
  void open() override;
  void close() override {}
  DeviceState read() override;
  bool sharesClock() const override { return true; }
  DeviceState readTick(const rt::TickTiming& timing) override;
  void write(const DeviceCommand& command) override;

  bool finished() const { return next_ >= samples_.size(); }
  std::size_t samplesPlayed() const { return next_ < samples_.size() ? next_ : samples_.size(); }
  std::size_t size() const { return samples_.size(); }
  double durationS() const;
  std::uint64_t writes() const { return writes_; }

 private:
  std::vector<ReplaySample> samples_;
  DeviceSpec spec_;
  ReplayOptions options_;
  rt::MonotonicClock monotonic_;
  rt::VirtualClock virtual_;
  rt::Pacer pacer_;
  std::size_t next_ = 0;
  // readTick(): the recorded tick minus the group's, set at the first readTick after open().
  bool group_started_ = false;
  std::int64_t tick_offset_ = 0;
  std::uint64_t writes_ = 0;
};

}  // namespace thx::dev
