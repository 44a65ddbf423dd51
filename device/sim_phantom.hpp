#pragma once
// SimPhantom: a simulated PHANToM held by a simulated hand, honouring the HapticDevice contract
// (haptic_device.hpp) so the servo cannot tell it from a real device. docs/design.md §5: it must be
// able to go unstable the way a real device does, so it integrates the pen + hand in continuous
// time far above the servo rate under a zero-order-hold motor force, quantises the encoders and
// reports finite-difference velocity.
//
// One device tick (read() returns at the tick's deadline):
//  1. wait for the tick on the Pacer (VirtualClock in lock-step: returns at once);
//  2. integrate every device period since the previous tick: 1 + timing.missed periods of
//     steps_per_tick steps each, the hand target sampled from the script at every step (on
//     config.surface_height's surface when one is given: hand_script.hpp);
//  3. motors over a period: the command of the last write() if one arrived since the previous
//     period started, otherwise the watchdog's hold: x decay^n for n = 1..hold periods, then
//     zero. The output is clipped to the spec's peak force (the motors saturate), direction kept;
//  4. reading: each world axis rounded to the encoder resolution; velocity = (reading - previous
//     reading) / elapsed time (a real driver's finite difference); the pen's fixed orientation
//     (SimPhantomConfig::pen_orientation, identity by default); button 1 (bit 0) while the hand
//     pushes; faults applied (SimFaults).
// A write() answering tick k drives the period [t_k, t_k+1]: zero extra delay, the sampled-data
// loop of the passivity analysis (b > K T / 2 + |B|).
//
// Real-time contract of read() and write(): no allocation, no locks, no exceptions, no logging;
// read() sleeps only in the Pacer. Its cost grows with 1 + missed (a stall is integrated, not
// skipped). Not thread-safe: one servo thread calls read()/write(); truth() and setFaults() from
// that thread (or between ticks).
#include <cstdint>
#include <memory>

#include "rt/clock.hpp"
#include "device/hand_script.hpp"
#include "device/haptic_device.hpp"
#include "rt/pacer.hpp"
#include "device/sim_config.hpp"
#include "device/sim_dynamics.hpp"

namespace thx::dev {

// Ground truth for analysis tools (energy, oscillation amplitude). Updated by every read().
struct SimTruth {
  std::int64_t tick = -1;  // TickTiming::tick of the last read()
  double t_s = 0.0;        // simulated time since open()
  Eigen::Vector3d p_world_m = Eigen::Vector3d::Zero();  // unquantised, at the tick
  Eigen::Vector3d v_world_m_per_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d motor_force_n = Eigen::Vector3d::Zero();  // applied in the last integration step
  bool motor_saturated = false;  // the peak-force clip acted during the last read()'s integration
  int watchdog_stale_periods = 0;  // periods since the last fresh write (0: the last was fresh)
  std::int64_t periods_integrated = 0;  // by the last read(): 1 + timing.missed
  Eigen::Vector3d hand_force_n = Eigen::Vector3d::Zero();  // at the tick
  HandTarget hand_target_world;                            // at the tick
  // Work of the motor force on the pen, sum of F . dx over the integration steps (= the integral
  // of F . v dt for the integrator's path): over the last read() and since open(). Positive: the
  // device injected energy.
  double motor_work_j = 0.0;
  double motor_work_total_j = 0.0;
  double kinetic_energy_j = 0.0;            // (m_pen + m_hand) |v|^2 / 2
  std::int64_t nonfinite_commands = 0;      // write()s whose force was not finite: rendered as zero
};

class SimPhantom final : public HapticDevice {
 public:
  // Throws DeviceError if the config is invalid (validate()). Without a clock it owns one:
  // VirtualClock when config.lockstep, MonotonicClock otherwise. An injected clock must outlive it.
  explicit SimPhantom(SimPhantomConfig config, HandScript script = HandScript(), rt::Clock* clock = nullptr);
  SimPhantom(const SimPhantom&) = delete;
  SimPhantom& operator=(const SimPhantom&) = delete;

  const DeviceSpec& spec() const override { return config_.spec; }
  OutputMode outputMode() const override { return config_.output_mode; }
  // Resets the simulation: the pen rests at the script's first target, no force, time 0, the
  // pacer's grid starts one period from now. Also re-opens after close().
  void open() override;
  void close() override;
  // Not open: returns at once with valid = false.
  DeviceState read() override;
  // The same at a tick a group's clock paced (server/servo_group.hpp): integrates 1 + missed
  // periods as read() does; this device's own pacer is not used.
  bool sharesClock() const override { return true; }
  DeviceState readTick(const rt::TickTiming& timing) override;
  // Not open: ignored. Non-finite forces are rendered as zero (counted in truth()).
  void write(const DeviceCommand& command) override;

  const SimTruth& truth() const { return truth_; }
  const SimPhantomConfig& config() const { return config_; }
  const HandScript& script() const { return script_; }
  rt::Clock& clock() { return *clock_; }
  int stepsPerTick() const { return steps_per_tick_; }
  void setFaults(const SimFaults& faults) { config_.faults = faults; }

 private:
  void integratePeriod(double& work_j, bool& saturated);
  Eigen::Vector3d motorForce(const SimBodyState& s, double gain, bool& saturated) const;
  Eigen::Vector3d quantise(const Eigen::Vector3d& p) const;
  double timeS() const { return double(step_index_) / double(config_.integration_hz); }

  SimPhantomConfig config_;
  HandScript script_;
  std::unique_ptr<rt::Clock> owned_clock_;
  rt::Clock* clock_;
  rt::Pacer pacer_;
  SimDynamics dynamics_;
  int steps_per_tick_;
  double period_s_;

  bool open_ = false;
  SimBodyState body_;
  std::int64_t step_index_ = 0;  // integration steps since open(): exact simulated time
  DeviceCommand held_;           // the last write()
  bool fresh_ = false;           // a write() arrived since the current period began
  int stale_periods_ = 0;
  double watchdog_gain_ = 0.0;
  Eigen::Vector3d last_count_m_ = Eigen::Vector3d::Zero();      // previous quantised reading
  Eigen::Vector3d last_delivered_m_ = Eigen::Vector3d::Zero();  // last reading handed out as valid
  SimTruth truth_;
};

}  // namespace thx::dev
