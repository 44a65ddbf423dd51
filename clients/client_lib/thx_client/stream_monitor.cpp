#include "thx_client/stream_monitor.hpp"

#include <algorithm>
#include <cmath>

namespace thx::client {

void StreamMonitor::received(std::int64_t server_utime_us, std::int64_t received_ns) {
  if (r_.messages == 0) first_ns_ = received_ns;
  last_ns_ = received_ns;
  ++r_.messages;
  if (received_ns - first_ns_ >= kSettleNs) {
    if (steady_messages_ == 0) first_steady_ns_ = received_ns;
    ++steady_messages_;
  }
  latencies_us_.push_back(double(received_ns) / 1e3 - double(server_utime_us));
}

void StreamMonitor::onMessage(std::int64_t tick, std::int64_t server_utime_us, std::int64_t received_ns) {
  if (any_ && tick <= last_tick_) {
    ++r_.duplicates;
    return;
  }
  if (any_ && rate_hz_ > 0.0) {
    const double periods = double(server_utime_us - last_utime_us_) * 1e-6 * rate_hz_;
    if (periods > 1.5) {
      ++r_.gaps;
      r_.missing += std::uint64_t(std::llround(periods)) - 1;
    }
  }
  any_ = true;
  last_tick_ = tick;
  last_utime_us_ = server_utime_us;
  received(server_utime_us, received_ns);
}

void StreamMonitor::serverRestarted() {
  if (!any_) return;
  any_ = false;
  ++r_.restarts;
}

void StreamMonitor::onBatch(const thx_msgs::contact_batch_t& b, std::int64_t received_ns) {
  if (any_ && b.server_instance != last_instance_) serverRestarted();
  last_instance_ = b.server_instance;
  if (any_ && b.seq <= last_seq_) {
    ++r_.duplicates;
    return;
  }
  if (any_) {
    if (b.seq > last_seq_ + 1) {
      ++r_.gaps;
      r_.missing += std::uint64_t(b.seq - last_seq_ - 1);
    }
    // The batch starts where the previous one ended, after the samples the server dropped.
    const std::int64_t start = b.next_tick - b.num_samples - b.num_dropped;
    if (start > last_next_tick_) r_.samples_missing += std::uint64_t(start - last_next_tick_);
  }
  for (std::size_t i = 1; i < b.samples.size(); ++i) {
    if (b.samples[i].tick <= b.samples[i - 1].tick) ++r_.samples_out_of_order;
  }
  any_ = true;
  last_seq_ = b.seq;
  last_next_tick_ = b.next_tick;
  if (r_.messages == 0) first_samples_ = std::uint64_t(b.num_samples);
  r_.samples += std::uint64_t(b.num_samples);
  r_.samples_dropped += std::uint64_t(std::max(0, b.num_dropped));
  received(b.samples.empty() ? b.utime : b.samples.back().utime, received_ns);
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
