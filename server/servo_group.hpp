#pragma once
// Several devices under one servo clock (issue 30). THIS FILE AND servo_group.cpp ARE ON THE
// REAL-TIME PATH, with servo.hpp's contract.
//
// One scheduler for every device, as OpenHaptics runs dual-device setups and CHAI3D's handler
// services its devices from one haptic thread: the group's Pacer waits for the tick, then every
// member servo ticks with that tick's timing (Servo::tickAt), in the order the members were added.
// A member's device is read with HapticDevice::readTick, which does not wait, so member k reads its
// device after members 0 .. k-1 have computed (a few µs each); its own pacer is not used.
//
// Each member is a whole servo (servo_rig.hpp): its own renderer and proxy, passivity controller,
// safety stage, missed-tick policy, latched faults, flight record and tick ring. The members share
// the clock and nothing else the tick writes, so a fault or a lost link on one device disengages
// that device's safety stage and no other's, and each device's force is the one it would get alone
// on the same clock (tests/server/test_servo_group.cpp holds them equal in lock-step).
//
// Contract of tick(): one wait on the group's clock (the pacer's sleep: the only system call);
// then the members' ticks; no allocation, lock or log. A missed period is missed by every member
// alike: they all see the same TickTiming. add() and start() run before the first tick.
#include <array>
#include <cstdint>

#include "rt/clock.hpp"
#include "rt/pacer.hpp"
#include "server/latency_histogram.hpp"
#include "server/servo.hpp"

namespace thx::srv {

class ServoGroup {
 public:
  // CHAI3D's device handler's limit; a scene may list at most this many devices.
  static constexpr int kMaxDevices = 16;

  // `clock` paces the group (MonotonicClock in real time, VirtualClock in lock-step) at `period_ns`;
  // spin_ns as rt::Pacer's. The clock must outlive the group.
  ServoGroup(rt::Clock& clock, std::int64_t period_ns, std::int64_t spin_ns = 0);
  ServoGroup(const ServoGroup&) = delete;
  ServoGroup& operator=(const ServoGroup&) = delete;

  // Before start(). Throws thx::Error (Config) naming the member when the group is full, the servo
  // is a member already, or its device cannot be read at another clock's tick
  // (HapticDevice::sharesClock()). The servo must outlive the group.
  void add(Servo& servo, const char* name = "");
  // After every member's device is open: the first deadline is one period from now.
  void start() { pacer_.start(); }

  struct Tick {
    rt::TickTiming timing;
    std::int64_t compute_ns = 0;  // from the group's wake to the end of its last member's tick
  };
  // Waits for the next deadline and ticks every member. Real-time safe.
  const Tick& tick();

  void requestShutdown();  // every member ramps its force down (its safety stage's shutdown)
  bool finished() const;   // every member has ramped down

  int size() const { return size_; }
  Servo& member(int i) { return *members_[std::size_t(i)]; }
  const Servo& member(int i) const { return *members_[std::size_t(i)]; }
  std::int64_t periodNs() const { return pacer_.periodNs(); }
  // The group's wake latency and compute time per tick (all members), as Servo's are one device's.
  const LatencyHistogram& computeHistogram() const { return compute_hist_; }
  const LatencyHistogram& wakeHistogram() const { return wake_hist_; }

 private:
  rt::Pacer pacer_;
  std::array<Servo*, kMaxDevices> members_{};
  int size_ = 0;
  Tick tick_;
  LatencyHistogram compute_hist_;
  LatencyHistogram wake_hist_;
};

}  // namespace thx::srv
