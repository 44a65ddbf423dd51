#include "device/sim_phantom.hpp"

#include <cmath>
#include <limits>
#include <utility>

#include "device/sim_planes.hpp"

namespace thx::dev {

namespace {

std::unique_ptr<rt::Clock> makeClock(bool lockstep, rt::Clock* injected) {
  if (injected) return nullptr;
  if (lockstep) return std::make_unique<rt::VirtualClock>();
  return std::make_unique<rt::MonotonicClock>();
}

const SimPhantomConfig& validated(const SimPhantomConfig& c) {
  validate(c);
  return c;
}

bool inWindow(std::int64_t tick, std::int64_t from, std::int64_t count) {
  return from >= 0 && count > 0 && tick >= from && tick - from < count;
}

}  // namespace

SimPhantom::SimPhantom(SimPhantomConfig config, HandScript script, rt::Clock* clock)
    : config_(validated(config)),
      script_(std::move(script)),
      owned_clock_(makeClock(config_.lockstep, clock)),
      clock_(clock ? clock : owned_clock_.get()),
      pacer_(*clock_, config_.servo_period_ns, config_.spin_ns),
      dynamics_(config_),
      steps_per_tick_(dev::stepsPerTick(config_)),
      period_s_(double(config_.servo_period_ns) * 1e-9) {}

void SimPhantom::open() {
  body_ = SimBodyState{};
  // At rest where the hand hovers.
  body_.x_m = script_.sample(0.0, config_.plane_to_world, config_.surface_height).p_m;
  step_index_ = 0;
  held_ = DeviceCommand{};
  fresh_ = false;
  stale_periods_ = config_.watchdog_hold_ticks + 1;  // nothing written yet: motors off
  watchdog_gain_ = 0.0;
  last_count_m_ = quantise(body_.x_m);
  last_delivered_m_ = last_count_m_;
  truth_ = SimTruth{};
  truth_.p_world_m = body_.x_m;
  truth_.hand_target_world = script_.sample(0.0, config_.plane_to_world, config_.surface_height);
  pacer_.start();
  open_ = true;
}

void SimPhantom::close() {
  open_ = false;
  held_ = DeviceCommand{};
  fresh_ = false;
}

void SimPhantom::write(const DeviceCommand& command) {
  if (!open_) return;
  held_ = command;
  if (config_.output_mode == OutputMode::Force && !held_.force_world_n.allFinite()) {
    held_.force_world_n.setZero();
    ++truth_.nonfinite_commands;
  }
  fresh_ = true;
}

Eigen::Vector3d SimPhantom::quantise(const Eigen::Vector3d& p) const {
  const double q = config_.encoder_resolution_m;
  return Eigen::Vector3d(std::round(p.x() / q) * q, std::round(p.y() / q) * q, std::round(p.z() / q) * q);
}

Eigen::Vector3d SimPhantom::motorForce(const SimBodyState& s, double gain, bool& saturated) const {
  if (gain == 0.0 || !held_.forces_enabled) return Eigen::Vector3d::Zero();
  Eigen::Vector3d f =
      gain * (config_.output_mode == OutputMode::Planes ? planeForce(held_, s) : held_.force_world_n);
  // The amplifiers saturate last, after the controller's watchdog: clip the magnitude, keep the
  // direction (a simplification of per-motor torque limits).
  const double magnitude = f.norm();
  if (magnitude > config_.spec.peak_force_n) {
    f *= config_.spec.peak_force_n / magnitude;
    saturated = true;
  }
  return f;
}

void SimPhantom::integratePeriod(double& work_j, bool& saturated) {
  if (fresh_) {
    fresh_ = false;
    stale_periods_ = 0;
    watchdog_gain_ = 1.0;
  } else if (stale_periods_ < config_.watchdog_hold_ticks) {
    ++stale_periods_;
    watchdog_gain_ *= config_.watchdog_decay;
  } else {
    stale_periods_ = config_.watchdog_hold_ticks + 1;  // saturates: no overflow on long runs
    watchdog_gain_ = 0.0;
  }

  // Force mode: the zero-order hold, one force for the whole period. Planes mode: the device's
  // own spring-dampers, re-evaluated every step.
  const bool planes = config_.output_mode == OutputMode::Planes;
  Eigen::Vector3d motor_n = planes ? Eigen::Vector3d::Zero() : motorForce(body_, watchdog_gain_, saturated);
  for (int k = 0; k < steps_per_tick_; ++k) {
    if (planes) motor_n = motorForce(body_, watchdog_gain_, saturated);
    const HandTarget target = script_.sample(timeS(), config_.plane_to_world, config_.surface_height);
    work_j += dynamics_.step(body_, motor_n, target);
    ++step_index_;
  }
  truth_.motor_force_n = motor_n;
}

DeviceState SimPhantom::read() {
  if (!open_) {
    DeviceState out;
    out.valid = false;
    return out;
  }
  return readTick(pacer_.wait());
}

DeviceState SimPhantom::readTick(const rt::TickTiming& timing) {
  DeviceState out;
  out.timing = timing;
  if (!open_) {
    out.valid = false;
    return out;
  }
  const std::int64_t periods = 1 + out.timing.missed;

  double work_j = 0.0;
  bool saturated = false;
  for (std::int64_t p = 0; p < periods; ++p) integratePeriod(work_j, saturated);

  const Eigen::Vector3d count_m = quantise(body_.x_m);
  const Eigen::Vector3d v_estimate = (count_m - last_count_m_) / (double(periods) * period_s_);
  last_count_m_ = count_m;

  const double t_s = timeS();
  const HandTarget target = script_.sample(t_s, config_.plane_to_world, config_.surface_height);
  out.p_world = count_m;
  out.v_world = v_estimate;
  out.q_world = config_.pen_orientation;
  out.buttons = target.pressing ? 1u : 0u;

  const std::int64_t tick = out.timing.tick;
  const SimFaults& f = config_.faults;
  if (inWindow(tick, f.nan_from_tick, f.nan_ticks)) {
    out.p_world.setConstant(std::numeric_limits<double>::quiet_NaN());
    out.v_world.setConstant(std::numeric_limits<double>::quiet_NaN());
  } else if (inWindow(tick, f.invalid_from_tick, f.invalid_ticks)) {
    out.valid = false;
    out.p_world = last_delivered_m_;
    out.v_world.setZero();
  } else {
    last_delivered_m_ = count_m;
  }

  truth_.tick = tick;
  truth_.t_s = t_s;
  truth_.p_world_m = body_.x_m;
  truth_.v_world_m_per_s = body_.v_m_per_s;
  truth_.motor_saturated = saturated;
  truth_.watchdog_stale_periods = stale_periods_;
  truth_.periods_integrated = periods;
  truth_.hand_force_n = dynamics_.handForce(body_, target);
  truth_.hand_target_world = target;
  truth_.motor_work_j = work_j;
  truth_.motor_work_total_j += work_j;
  truth_.kinetic_energy_j = 0.5 * dynamics_.massKg() * body_.v_m_per_s.squaredNorm();
  return out;
}

}  // namespace thx::dev
