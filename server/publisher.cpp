#include "server/publisher.hpp"

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <thx_msgs/contact_t.hpp>
#include <thx_msgs/device_state_t.hpp>
#include <thx_msgs/servo_stats_t.hpp>

#include "server/process_memory.hpp"
#include "server/safety.hpp"

namespace thx::srv {

namespace {

std::int64_t monotonicNs() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return std::int64_t(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

template <std::size_t N>
void copy(double (&dst)[N], const double (&src)[N]) {
  for (std::size_t k = 0; k < N; ++k) dst[k] = src[k];
}

constexpr char kDeviceStateChannel[] = "THX_DEVICE_STATE";
constexpr char kContactChannel[] = "THX_CONTACT";
constexpr char kServoStatsChannel[] = "THX_SERVO_STATS";

}  // namespace

Publisher::Publisher(SpscRing<TickRecord>& ring, const Servo& servo, FlightRecorder& recorder, lcm::LCM* lcm,
                     const PublisherOptions& options)
    : ring_(ring), servo_(servo), recorder_(recorder), lcm_(lcm), options_(options) {
  const double ratio = options.servo_rate_hz / std::fmax(1e-9, options.publish_hz);
  decimation_ = std::max<std::int64_t>(1, std::llround(ratio));
}

Publisher::~Publisher() { stop(); }

void Publisher::start() {
  last_stats_ns_ = monotonicNs();
  thread_ = std::thread([this] { run(); });
}

void Publisher::stop() {
  if (!thread_.joinable()) return;
  stop_.store(true);
  thread_.join();
}

PublisherCounters Publisher::counters() const {
  return {records_.load(), published_.load(), publish_errors_.load(), flight_dumps_.load()};
}

std::string Publisher::lastFlightDump() const {
  while (dump_lock_.exchange(true)) {
  }
  std::string copy_of = last_dump_;
  dump_lock_.store(false);
  return copy_of;
}

void Publisher::run() {
  TickRecord r;
  for (;;) {
    const bool stopping = stop_.load();
    while (ring_.pop(r)) {
      records_.fetch_add(1, std::memory_order_relaxed);
      ++ticks_seen_;
      missed_seen_ += std::uint64_t(r.missed);
      const double f = std::sqrt(r.f_out[0] * r.f_out[0] + r.f_out[1] * r.f_out[1] + r.f_out[2] * r.f_out[2]);
      if (f > window_max_force_n_) window_max_force_n_ = f;
      if (r.tick % decimation_ == 0) publishRecord(r);
    }
    dumpFlight();
    const std::int64_t now = monotonicNs();
    if (now - last_stats_ns_ >= 1'000'000'000) publishStats(now);
    if (stopping) break;
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
}

void Publisher::publishRecord(const TickRecord& r) {
  if (!lcm_) return;
  thx_msgs::device_state_t d{};
  d.utime = r.deadline_ns / 1000;
  d.tick = r.tick;
  copy(d.p_world, r.p_world);
  copy(d.q_world, r.q_world);
  copy(d.v_world, r.v_world);
  d.buttons = std::int32_t(r.buttons);
  copy(d.f_cmd_world, r.f_out);
  std::int32_t flags = 0;
  if (!(r.safety_flags & (kSafetyDisengaged | kSafetyShutDown))) flags |= thx_msgs::device_state_t::FLAG_ENGAGED;
  if (r.safety_flags & (kSafetyEngaging | kSafetyRampingOut)) flags |= thx_msgs::device_state_t::FLAG_RAMPING;
  if (r.safety_flags & kSafetyClampMask) flags |= thx_msgs::device_state_t::FLAG_SAFETY_CLAMP;
  if (r.in_contact) flags |= thx_msgs::device_state_t::FLAG_IN_CONTACT;
  if (r.missed > 0) flags |= thx_msgs::device_state_t::FLAG_MISSED_TICK;
  if (r.f_client[0] != 0.0 || r.f_client[1] != 0.0 || r.f_client[2] != 0.0) {
    flags |= thx_msgs::device_state_t::FLAG_CLIENT_FORCE;
  }
  if (options_.simulated_device) flags |= thx_msgs::device_state_t::FLAG_SIMULATED;
  if (r.faults) flags |= thx_msgs::device_state_t::FLAG_FAULT;
  d.flags = flags;
  using D = thx_msgs::device_state_t;
  d.fault_code = std::int32_t{D::FAULT_NONE};
  if (r.faults & kFaultInvalidReading) d.fault_code = std::int32_t{D::FAULT_DEVICE_REPORTED};
  if (r.faults & kFaultNonFiniteForce) d.fault_code = std::int32_t{D::FAULT_NONFINITE_FORCE};
  if (r.faults & kFaultMissedTicks) d.fault_code = std::int32_t{D::FAULT_MISSED_TICKS};

  thx_msgs::contact_t c{};
  c.utime = d.utime;
  c.tick = r.tick;
  c.in_contact = r.in_contact;
  c.num_planes = r.num_planes;
  c.surface_id = 0;
  c.texel_i = r.texel_i;
  c.texel_j = r.texel_j;
  copy(c.p_proj_world, r.p_proj_world);
  copy(c.uv, r.uv);
  copy(c.n_geom_world, r.n_geom_world);
  copy(c.n_sampled_world, r.n_sampled_world);
  c.depth = r.depth_m;
  c.relief_depth = r.relief_depth_m;
  for (int i = 0; i < 4; ++i) {
    copy(c.plane_n_world[i], r.plane_n_world[i]);
    c.plane_d[i] = r.plane_d_m[i];
  }
  c.f_normal = r.f_normal_n;
  for (int k = 0; k < 3; ++k) c.f_normal_world[k] = r.f_normal_n * r.plane_n_world[0][k];
  copy(c.v_tangent_world, r.v_tangent_world);

  const int a = lcm_->publish(kDeviceStateChannel, &d);
  const int b = lcm_->publish(kContactChannel, &c);
  published_.fetch_add(2, std::memory_order_relaxed);
  if (a != 0 || b != 0) publish_errors_.fetch_add(1, std::memory_order_relaxed);
}

void Publisher::publishStats(std::int64_t now_ns) {
  const std::uint64_t ticks = ticks_seen_, missed = missed_seen_;
  const double window_s = double(now_ns - last_stats_ns_) * 1e-9;
  if (lcm_) {
    thx_msgs::servo_stats_t s{};
    s.utime = now_ns / 1000;
    s.ticks = std::int64_t(ticks);
    s.missed_ticks = std::int64_t(missed);
    s.window_ticks = std::int64_t(ticks - last_stats_ticks_);
    s.window_missed_ticks = std::int64_t(missed - last_stats_missed_);
    s.window_s = window_s;
    s.rate_nominal_hz = options_.servo_rate_hz;
    s.rate_hz = window_s > 0 ? double(s.window_ticks) / window_s : 0.0;
    const LatencyHistogram& c = servo_.computeHistogram();
    const LatencyHistogram& w = servo_.wakeHistogram();
    s.compute_p50_us = c.quantileUs(0.5);
    s.compute_p99_us = c.quantileUs(0.99);
    s.compute_p999_us = c.quantileUs(0.999);
    s.compute_max_us = double(c.maxNs()) / 1e3;
    s.wake_p50_us = w.quantileUs(0.5);
    s.wake_p99_us = w.quantileUs(0.99);
    s.wake_p999_us = w.quantileUs(0.999);
    s.wake_max_us = double(w.maxNs()) / 1e3;
    s.f_max = window_max_force_n_;
    s.snapshots_dropped = std::int64_t(ring_.dropped());
    s.rss_bytes = readProcessMemory().rss_bytes;
    if (lcm_->publish(kServoStatsChannel, &s) != 0) publish_errors_.fetch_add(1, std::memory_order_relaxed);
  }
  last_stats_ns_ = now_ns;
  last_stats_ticks_ = ticks;
  last_stats_missed_ = missed;
  window_max_force_n_ = 0.0;
}

void Publisher::dumpFlight() {
  try {
    const std::string path = recorder_.dumpPending(options_.flight_dir);
    if (path.empty()) return;
    flight_dumps_.fetch_add(1);
    while (dump_lock_.exchange(true)) {
    }
    last_dump_ = path;
    dump_lock_.store(false);
    std::fprintf(stderr, "hapticd: fault: flight record written to %s\n", path.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hapticd: %s\n", e.what());
  }
}

}  // namespace thx::srv
