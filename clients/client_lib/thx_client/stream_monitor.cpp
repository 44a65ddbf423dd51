#include "thx_client/stream_monitor.hpp"

#include <algorithm>
#include <cmath>

namespace thx::client {

StreamMonitor::Track* StreamMonitor::track(int device) {
  if (device >= 0 && device < kMaxDevices) return &tracks_[std::size_t(device)];
  ++r_.outside_devices;
  return nullptr;
}

bool StreamMonitor::duplicate(bool older, int device) {
  if (!older) return false;
  ++r_.duplicates;
  ++r_.by_device[std::size_t(device)].duplicates;
  return true;
}

void StreamMonitor::gap(int device, std::uint64_t missing) {
  ++r_.gaps;
  r_.missing += missing;
  DeviceCounts& d = r_.by_device[std::size_t(device)];
  ++d.gaps;
  d.missing += missing;
}

void StreamMonitor::received(int device, std::int64_t server_utime_us, std::int64_t received_ns) {
  any_ = true;
  ++r_.by_device[std::size_t(device)].messages;
  if (r_.messages == 0) first_ns_ = received_ns;
  last_ns_ = received_ns;
  ++r_.messages;
  if (received_ns - first_ns_ >= kSettleNs) {
    if (steady_messages_ == 0) first_steady_ns_ = received_ns;
    ++steady_messages_;
  }
  latencies_us_.push_back(double(received_ns) / 1e3 - double(server_utime_us));
}

void StreamMonitor::onMessage(std::int64_t tick, std::int64_t server_utime_us, std::int64_t received_ns, int device) {
  Track* t = track(device);
  if (!t || duplicate(t->any && tick <= t->last_tick, device)) return;
  if (t->any && rate_hz_ > 0.0) {
    const double periods = double(server_utime_us - t->last_utime_us) * 1e-6 * rate_hz_;
    if (periods > 1.5) gap(device, std::uint64_t(std::llround(periods)) - 1);
  }
  t->any = true;
  t->last_tick = tick;
  t->last_utime_us = server_utime_us;
  received(device, server_utime_us, received_ns);
}

void StreamMonitor::serverRestarted() {
  if (!any_) return;
  any_ = false;
  for (Track& t : tracks_) t.any = false;
  ++r_.restarts;
}

void StreamMonitor::onBatch(const thx_msgs::contact_batch_t& b, std::int64_t received_ns) {
  if (any_ && b.server_instance != last_instance_) serverRestarted();
  last_instance_ = b.server_instance;
  Track* t = track(b.device);
  if (!t || duplicate(t->any && b.seq <= t->last_seq, b.device)) return;
  if (t->any) {
    if (b.seq > t->last_seq + 1) gap(b.device, std::uint64_t(b.seq - t->last_seq - 1));
    // The batch starts where the device's previous one ended, after the samples the server dropped.
    const std::int64_t start = b.next_tick - b.num_samples - b.num_dropped;
    if (start > t->last_next_tick) r_.samples_missing += std::uint64_t(start - t->last_next_tick);
  }
  for (std::size_t i = 1; i < b.samples.size(); ++i) {
    if (b.samples[i].tick <= b.samples[i - 1].tick) ++r_.samples_out_of_order;
  }
  t->any = true;
  t->last_seq = b.seq;
  t->last_next_tick = b.next_tick;
  if (r_.messages == 0) first_samples_ = std::uint64_t(b.num_samples);
  r_.samples += std::uint64_t(b.num_samples);
  r_.samples_dropped += std::uint64_t(std::max(0, b.num_dropped));
  received(b.device, b.samples.empty() ? b.utime : b.samples.back().utime, received_ns);
}

StreamReport StreamMonitor::report() const {
  StreamReport out = r_;
  out.span_s = double(last_ns_ - first_ns_) * 1e-9;
  if (out.messages > 1 && out.span_s > 0) {
    out.achieved_rate_hz = double(out.messages - 1) / out.span_s;
    out.sample_rate_hz = double(out.samples - first_samples_) / out.span_s;  // samples after the first receipt
  }
  if (steady_messages_ > 1 && last_ns_ > first_steady_ns_) {
    out.steady_rate_hz = double(steady_messages_ - 1) / (double(last_ns_ - first_steady_ns_) * 1e-9);
  }
  if (!latencies_us_.empty()) {
    std::vector<double> l = latencies_us_;
    std::sort(l.begin(), l.end());
    auto q = [&](double p) { return l[std::min(l.size() - 1, std::size_t(p * double(l.size() - 1) + 0.5))]; };
    out.latency_p50_us = q(0.5);
    out.latency_p99_us = q(0.99);
    out.latency_max_us = l.back();
  }
  return out;
}

}  // namespace thx::client
