#pragma once
// The servo run loop: ticks a Servo (server/servo.hpp), or several devices' servos under one
// clock (server/servo_group.hpp), from the first deadline to the end of the ramp-down, on a
// real-time thread of its own (hapticd: start()) or on the caller's (tests: step(), run()).
//
// Real-time contract of the loop (docs/hapticd.md, "the servo tick never blocks"):
// - Each tick may: read the device (its blocking read is the pacing sleep), compute, write the
//   device, push the tick's record into the ring (lock-free; a full ring drops the record and
//   counts it), read and write atomics (the stop flag, the tick count).
// - It may not: allocate, take a lock, log, or make any system call besides the pacing sleep and
//   the device's I/O. What can fail or block (making the thread real-time, device.open()) happens
//   before the first tick; its errors are read after join(), never reported from the loop.
// - Lock-step back-pressure: under lock-step (a virtual clock, not real time) the loop does not
//   tick while the ring (a group: any member's ring) holds capacity - 2 records or more; run() sleeps 100 us and looks again, so
//   the ring's reader (the publisher, and --record behind it) never misses a tick. It sleeps, not
//   yields: a yielding SCHED_FIFO thread gives its core only to threads of its own priority or
//   higher, so with two lock-step runs on two cores neither publisher (an ordinary thread under
//   lock-step) got a core, and both livelocked. In real time the servo never waits for a reader.
// - Stop: stop(), the external stop flag (a signal handler's) or the first tick numbered at or
//   after stop_tick asks the servo to shut down, once; the loop keeps ticking through the safety
//   stage's ramp-down and ends when Servo::finished() (zero force).
#include <atomic>
#include <cstdint>
#include <string>
#include <thread>

#include "device/haptic_device.hpp"
#include "rt/spsc_ring.hpp"
#include "server/realtime.hpp"
#include "server/servo.hpp"
#include "server/servo_group.hpp"
#include "server/tick_record.hpp"

namespace thx::srv {

struct ServoRunnerOptions {
  bool lockstep = false;         // wait for the ring's reader instead of dropping ticks
  std::int64_t stop_tick = -1;   // ramp down from this tick on; -1: only when stopped
  const std::atomic<bool>* stop_flag = nullptr;  // e.g. set on SIGINT/SIGTERM; not owned
};

// The first tick of the ramp-down after `duration_s` seconds at `rate_hz`; -1 (run until stopped)
// for a duration of 0.
std::int64_t stopTickAfter(double duration_s, double rate_hz);

class ServoRunner {
 public:
  enum class Step { Ticked, WaitingForReader, Finished };

  // `ring` is the one the servo pushes its records into (ServoRig::ring()). Both outlive the runner.
  ServoRunner(Servo& servo, const rt::SpscRing<TickRecord>& ring, const ServoRunnerOptions& options);
  // Several devices: the group's ticks, back-pressure on its members' rings. The group outlives the
  // runner.
  ServoRunner(ServoGroup& group, const ServoRunnerOptions& options);
  ~ServoRunner();  // joins the thread start() began
  ServoRunner(const ServoRunner&) = delete;
  ServoRunner& operator=(const ServoRunner&) = delete;

  // One pass of the loop on the calling thread: Finished once the ramp-down has ended;
  // WaitingForReader (no tick) under lock-step while the ring is nearly full; else one tick.
  Step step();
  // step() until Finished, sleeping 100 us after each WaitingForReader.
  void run();

  // The servo thread: makes itself real-time (`rt`), opens the device (so its clock starts only
  // now: locking memory takes milliseconds, which would count as missed ticks), then run().
  void start(dev::HapticDevice& device, const RealtimeOptions& rt);
  // The same with the servo's own device, or for a group: every member's device opened in order
  // (those opened are closed again if one fails), then the group's clock started.
  void start(const RealtimeOptions& rt);
  bool done() const { return done_.load(); }  // the thread has ended: finished, or did not start
  void join();
  // After join(): why the servo did not run ("" when it did), and what the real-time setup got.
  const std::string& error() const { return error_; }
  const RealtimeReport& realtime() const { return realtime_; }

  void stop() { stop_requested_.store(true, std::memory_order_relaxed); }  // any thread
  std::int64_t ticks() const { return ticks_.load(std::memory_order_relaxed); }  // any thread
  // Device time from the first tick's deadline to the end of the last tick (after join()).
  double deviceTimeS(double period_s) const { return double(last_deadline_ns_ - first_deadline_ns_) * 1e-9 + period_s; }

 private:
  bool finished() const { return group_ ? group_->finished() : servo_->finished(); }
  bool readerBehind() const;
  void openAndRun(const RealtimeOptions& rt, dev::HapticDevice* device);

  Servo* servo_ = nullptr;  // one device, or
  ServoGroup* group_ = nullptr;  // several
  const rt::SpscRing<TickRecord>* ring_ = nullptr;  // one device's
  ServoRunnerOptions options_;
  std::atomic<bool> stop_requested_{false};
  std::atomic<bool> done_{false};
  std::atomic<std::int64_t> ticks_{0};
  bool shutting_down_ = false;
  std::int64_t first_deadline_ns_ = 0, last_deadline_ns_ = 0;
  std::string error_;  // written by the servo thread before it sets done_
  RealtimeReport realtime_;
  std::thread thread_;
};

}  // namespace thx::srv
