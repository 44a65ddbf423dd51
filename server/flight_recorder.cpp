#include "server/flight_recorder.hpp"

#include "base/error.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace thx::srv {

FlightRecorder::FlightRecorder(std::size_t capacity) : capacity_(capacity < 1 ? 1 : capacity) {
  for (Buffer& b : buffers_) b.records = std::make_unique<FlightRecord[]>(capacity_);
}

FlightRecorder::FlightRecord FlightRecorder::slim(const TickRecord& r) {
  FlightRecord s;
  s.tick = r.tick;
  s.wake_latency_ns = r.wake_latency_ns;
  s.compute_ns = r.compute_ns;
  s.missed = r.missed;
  s.valid = r.valid;
  s.in_contact = r.in_contact;
  s.recovering = r.recovering;
  s.num_planes = r.num_planes;
  std::copy_n(r.p_world, 3, s.p_world);
  std::copy_n(r.v_world, 3, s.v_world);
  s.depth_m = r.depth_m;
  std::copy_n(r.f_render, 3, s.f_render);
  std::copy_n(r.f_client, 3, s.f_client);
  std::copy_n(r.f_passive, 3, s.f_passive);
  std::copy_n(r.f_out, 3, s.f_out);
  s.pc_energy_j = r.pc_energy_j;
  s.pc_damping_ns_per_m = r.pc_damping_ns_per_m;
  s.safety_flags = r.safety_flags;
  s.faults = r.faults;
  return s;
}

void FlightRecorder::record(const TickRecord& r) {
  Buffer& b = buffers_[active_];
  b.records[b.next] = slim(r);
  b.next = (b.next + 1) % capacity_;
  if (b.filled < capacity_) ++b.filled;
}

void FlightRecorder::freeze(std::uint32_t fault_bits, std::int64_t tick) {
  faults_.store(faults_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
  if (frozen_.load(std::memory_order_acquire)) {
    not_frozen_.store(not_frozen_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
    return;
  }
  frozen_fault_ = fault_bits;
  frozen_tick_ = tick;
  active_ = 1 - active_;
  buffers_[active_].next = 0;
  buffers_[active_].filled = 0;
  frozen_.store(true, std::memory_order_release);
}

std::string faultName(std::uint32_t bits) {
  std::string name;
  auto add = [&](std::uint32_t bit, const char* text) {
    if (!(bits & bit)) return;
    if (!name.empty()) name += "+";
    name += text;
  };
  add(kFaultInvalidReading, "invalid-reading");
  add(kFaultMissedTicks, "missed-ticks");
  add(kFaultNonFiniteForce, "non-finite-force");
  add(kFaultForceBudget, "force-budget");
  return name.empty() ? "none" : name;
}

std::optional<std::int64_t> FlightRecorder::pendingTick() const {
  if (!frozen_.load(std::memory_order_acquire)) return std::nullopt;
  return frozen_tick_;
}

void FlightRecorder::discardPending() { frozen_.store(false, std::memory_order_release); }

std::string FlightRecorder::dumpPending(const std::string& directory, const std::string& tag) {
  if (!frozen_.load(std::memory_order_acquire)) return {};
  const Buffer& b = buffers_[1 - active_];
  const std::string path = directory + "/flight-" + (tag.empty() ? "" : tag + "-") + "tick" + std::to_string(frozen_tick_) + "-" + faultName(frozen_fault_) + ".csv";
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) {
    frozen_.store(false, std::memory_order_release);  // report once, then keep recording
    throw thx::Error(thx::Error::Kind::Io, "cannot write flight record " + path + ": check --flight-dir");
  }
  std::fprintf(f, "# flight record: %zu ticks before fault '%s' at tick %lld\n", b.filled,
               faultName(frozen_fault_).c_str(), (long long)frozen_tick_);
  std::fprintf(f,
               "tick,missed,wake_latency_us,compute_us,valid,px,py,pz,vx,vy,vz,in_contact,recovering,num_planes,"
               "depth_m,f_render_x,f_render_y,f_render_z,f_client_x,f_client_y,f_client_z,f_passive_x,f_passive_y,"
               "f_passive_z,f_out_x,f_out_y,f_out_z,pc_energy_j,pc_damping,safety_flags,faults\n");
  const std::size_t start = b.filled < capacity_ ? 0 : b.next;
  for (std::size_t k = 0; k < b.filled; ++k) {
    const FlightRecord& r = b.records[(start + k) % capacity_];
    std::fprintf(f,
                 "%lld,%d,%.3f,%.3f,%d,%.9g,%.9g,%.9g,%.6g,%.6g,%.6g,%d,%d,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,"
                 "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%u,%u\n",
                 (long long)r.tick, r.missed, double(r.wake_latency_ns) / 1e3, double(r.compute_ns) / 1e3,
                 int(r.valid), r.p_world[0], r.p_world[1], r.p_world[2], r.v_world[0], r.v_world[1], r.v_world[2],
                 int(r.in_contact), int(r.recovering), int(r.num_planes), r.depth_m, r.f_render[0], r.f_render[1],
                 r.f_render[2], r.f_client[0], r.f_client[1], r.f_client[2], r.f_passive[0], r.f_passive[1],
                 r.f_passive[2], r.f_out[0], r.f_out[1], r.f_out[2], r.pc_energy_j, r.pc_damping_ns_per_m,
                 r.safety_flags, r.faults);
  }
  const bool ok = std::fclose(f) == 0;
  frozen_.store(false, std::memory_order_release);
  if (!ok) throw thx::Error(thx::Error::Kind::Io, "cannot write flight record " + path);
  return path;
}

}  // namespace thx::srv
