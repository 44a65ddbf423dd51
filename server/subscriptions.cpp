#include "server/subscriptions.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <thx_msgs/protocol.hpp>

#include "base/error.hpp"

namespace thx::srv {

namespace {

using Req = thx_msgs::subscribe_request_t;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// A peer's string made safe to quote in a reason: printable ASCII, at most 40 characters.
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (std::size_t i = 0; i < s.size() && i < 40; ++i) out += (s[i] >= 32 && s[i] < 127) ? s[i] : '?';
  if (s.size() > 40) out += "...";
  return out + "'";
}

std::size_t encodedSize(StreamKind kind) {
  switch (kind) {
    case StreamKind::DeviceState: return std::size_t(thx_msgs::device_state_t{}.getEncodedSize());
    case StreamKind::Contact: return std::size_t(thx_msgs::contact_t{}.getEncodedSize());
    case StreamKind::ContactBatch: return thx_msgs::kBatchHeaderBytes;
    case StreamKind::ServoStats: return std::size_t(thx_msgs::servo_stats_t{}.getEncodedSize());
  }
  return 0;
}

}  // namespace

double streamBandwidth(StreamKind kind, double rate_hz, double servo_rate_hz, std::size_t channel_length) {
  // LCM 1.3.1 udpm short message: 8-byte header (magic, sequence), channel, NUL, payload.
  const double per_message = double(encodedSize(kind) + channel_length + 1 + 8);
  double bytes = rate_hz * per_message;
  if (kind == StreamKind::ContactBatch) bytes += servo_rate_hz * double(thx_msgs::contact_sample_encoded_size());
  return bytes;
}

SubscriptionTable::SubscriptionTable(const SubscriptionLimits& limits) : limits_(limits) {
  if (limits_.devices < 1 || limits_.devices > SubscriptionLimits::kMaxDevices) {
    throw Error(Error::Kind::Config, "subscription table: devices = " + std::to_string(limits_.devices) +
                                         ": expected 1 to " + std::to_string(SubscriptionLimits::kMaxDevices));
  }
  stats_windows_.assign(std::size_t(limits_.devices), 0);
}

thx_msgs::subscribe_reply_t SubscriptionTable::refuse(thx_msgs::subscribe_reply_t reply, std::string reason) {
  ++counters_.refused;
  reply.accepted = false;
  reply.reason = std::move(reason);
  reply.rate_hz = 0.0;
  reply.batch = false;
  reply.channel.clear();
  return reply;
}

thx_msgs::subscribe_reply_t SubscriptionTable::handleRequest(const Req& req, std::int64_t now_ns) {
  ++counters_.requests;
  thx_msgs::subscribe_reply_t reply{};
  reply.server_instance = limits_.server_instance;
  reply.request_seq = req.seq;
  reply.client_id = thx_msgs::is_valid_client_id(req.client_id) ? req.client_id : quoted(req.client_id);
  reply.stream = thx_msgs::is_known_stream(req.stream) ? req.stream : quoted(req.stream);
  reply.action = req.action;
  reply.heartbeat_timeout_us = limits_.heartbeat_timeout_ns / 1000;

  if (!thx_msgs::is_valid_client_id(req.client_id)) {
    return refuse(reply, "invalid client_id " + quoted(req.client_id) + ": expected 1 to 32 characters of [A-Za-z0-9_-]");
  }
  if (req.action != Req::ACTION_SUBSCRIBE && req.action != Req::ACTION_UNSUBSCRIBE) {
    return refuse(reply, "unknown action " + std::to_string(req.action) + ": expected 1 (subscribe) or 2 (unsubscribe)");
  }
  if (!thx_msgs::is_known_stream(req.stream)) {
    return refuse(reply, "unknown stream " + quoted(req.stream) + ": expected DEVICE_STATE, CONTACT or SERVO_STATS");
  }
  auto client_it = clients_.find(req.client_id);

  if (req.action == Req::ACTION_UNSUBSCRIBE) {
    if (client_it != clients_.end()) {
      if (auto sub = client_it->second.subs.find(req.stream); sub != client_it->second.subs.end()) {
        retire(sub->second);
        client_it->second.subs.erase(sub);
      }
      heardFrom(client_it->second, client_it->first, now_ns);
      if (client_it->second.subs.empty()) forget(client_it);
      recount();
    }
    reply.accepted = true;  // unsubscribing what is not there is already done
    return reply;
  }

  const bool batch = req.batch != 0;
  if (batch && !thx_msgs::stream_supports_batch(req.stream)) {
    return refuse(reply, "batching is only available for CONTACT, not " + req.stream);
  }
  if (!std::isfinite(req.rate_hz) || req.rate_hz <= 0.0) {
    return refuse(reply, "rate_hz must be a finite number > 0, got " + num(req.rate_hz));
  }
  StreamKind kind = StreamKind::DeviceState;
  if (req.stream == thx_msgs::kStreamContact) kind = batch ? StreamKind::ContactBatch : StreamKind::Contact;
  if (req.stream == thx_msgs::kStreamServoStats) kind = StreamKind::ServoStats;
  const std::string channel = thx_msgs::stream_channel(req.stream, batch, req.client_id);

  // The granted rate: as asked, within [floor, cap].
  double cap = std::min(limits_.servo_rate_hz, limits_.max_rate_hz);
  std::string cap_why = limits_.max_rate_hz < limits_.servo_rate_hz ? "the server's maximum rate (hapticd --max-rate)"
                                                                     : "the servo rate";
  if (kind == StreamKind::ServoStats && 1.0 / limits_.stats_window_s < cap) {
    cap = 1.0 / limits_.stats_window_s;
    cap_why = "one SERVO_STATS window per " + num(limits_.stats_window_s) + " s";
  }
  double rate = req.rate_hz;
  std::string adjusted;
  std::size_t max_samples = 0;
  if (rate > cap) {
    rate = cap;
    adjusted = "asked " + num(req.rate_hz) + " Hz, granted " + num(rate) + " Hz: " + cap_why;
  }
  if (kind == StreamKind::ContactBatch) {
    // Keep every batch within one UDP datagram (a lost fragment would lose the whole batch).
    max_samples = thx_msgs::max_unfragmented_batch_samples(channel.size());
    const double floor = limits_.servo_rate_hz / double(max_samples);
    if (rate < floor) {
      rate = floor;
      adjusted = "asked " + num(req.rate_hz) + " Hz, granted " + num(rate) + " Hz: a batch holds at most " +
                 std::to_string(max_samples) + " samples (one UDP datagram)";
    }
  }

  const bool new_client = client_it == clients_.end();
  if (new_client && int(clients_.size()) >= limits_.max_clients) {
    return refuse(reply, "too many clients: " + std::to_string(clients_.size()) + " connected, the limit is " +
                             std::to_string(limits_.max_clients) + " (hapticd --max-clients)");
  }
  // Every device's messages go out on the channel.
  const double need = double(limits_.devices) * streamBandwidth(kind, rate, limits_.servo_rate_hz, channel.size());
  double in_use = bandwidth();
  Subscription* old = nullptr;
  if (!new_client) {
    auto s = client_it->second.subs.find(req.stream);
    if (s != client_it->second.subs.end()) {
      old = &s->second;
      in_use -= old->bytes_per_s;  // a replacement frees what it replaces
    }
  }
  if (in_use + need > limits_.max_bandwidth_bytes_per_s) {
    return refuse(reply, "bandwidth limit: this subscription needs " + num(need / 1e3) + " kB/s, " +
                             num(in_use / 1e3) + " of " + num(limits_.max_bandwidth_bytes_per_s / 1e3) +
                             " kB/s are in use (hapticd --max-bandwidth)");
  }

  int data_port = new_client ? 0 : client_it->second.data_port;
  if (new_client && ports_) {
    const std::optional<int> port = ports_->acquire(req.client_id);
    if (!port) return refuse(reply, ports_->exhaustedReason());
    data_port = *port;
  }
  Client& client = clients_[req.client_id];
  if (new_client) client.last_seen_ns = now_ns;
  heardFrom(client, req.client_id, now_ns);
  client.data_port = data_port;
  // A resend of the same subscription (a lost reply) keeps its schedule and batch sequence.
  const bool same = old && old->kind == kind && old->rate_hz == rate && old->channel == channel;
  if (!same) {
    if (old) retire(*old);  // a batch replacing a batch on its channel continues its sequence
    Subscription s;
    s.kind = kind;
    s.channel = channel;
    s.rate_hz = rate;
    s.period = kind == StreamKind::ServoStats ? 1.0 / (rate * limits_.stats_window_s) : limits_.servo_rate_hz / rate;
    s.bytes_per_s = need;
    s.data_port = data_port;
    s.max_samples = max_samples;
    s.devices.resize(std::size_t(limits_.devices));
    if (kind == StreamKind::ContactBatch) {
      for (std::size_t d = 0; d < s.devices.size(); ++d) {
        thx_msgs::contact_batch_t& b = s.devices[d].batch;
        b.server_instance = limits_.server_instance;
        b.device = std::int32_t(d);
        b.samples.reserve(max_samples);  // allocated once, reused for every batch
        if (auto r = retired_batch_seq_.find({channel, int(d)}); r != retired_batch_seq_.end()) {
          b.seq = r->second;  // the sequence goes on where this channel's last batch of d left it
          retired_batch_seq_.erase(r);
        }
      }
    }
    client.subs[req.stream] = std::move(s);
  }
  recount();

  reply.accepted = true;
  reply.reason = adjusted;
  reply.rate_hz = rate;
  reply.batch = batch;
  reply.channel = channel;
  if (ports_) reply.data_url = ports_->url(data_port);
  return reply;
}

void SubscriptionTable::forget(std::map<std::string, Client>::iterator it) {
  for (const auto& [stream, sub] : it->second.subs) retire(sub);
  if (ports_) ports_->release(it->first);
  clients_.erase(it);
}

void SubscriptionTable::retire(const Subscription& s) {
  if (s.kind != StreamKind::ContactBatch) return;
  for (std::size_t d = 0; d < s.devices.size(); ++d) {
    if (s.devices[d].batch.seq == 0) continue;
    if (retired_batch_seq_.size() >= kMaxRetiredChannels * std::size_t(limits_.devices)) retired_batch_seq_.clear();
    retired_batch_seq_[{s.channel, int(d)}] = s.devices[d].batch.seq;
  }
}

void SubscriptionTable::heardFrom(Client& client, const std::string& id, std::int64_t now_ns) {
  if (client.suspended) {
    client.suspended = false;
    ++counters_.resumed_clients;
    changes_.push_back({id, true, now_ns - client.last_seen_ns});
  }
  client.last_seen_ns = std::max(client.last_seen_ns, now_ns);
}

std::vector<SubscriptionTable::ClientChange> SubscriptionTable::takeChanges() {
  std::vector<ClientChange> out;
  out.swap(changes_);
  return out;
}

bool SubscriptionTable::heartbeat(const thx_msgs::heartbeat_t& hb, std::int64_t now_ns) {
  auto it = clients_.find(hb.client_id);
  if (it == clients_.end()) {
    ++counters_.unknown_heartbeats;
    return false;
  }
  ++counters_.heartbeats;
  heardFrom(it->second, it->first, now_ns);
  return true;
}

std::vector<std::string> SubscriptionTable::expire(std::int64_t now_ns) {
  std::vector<std::string> gone;
  for (auto it = clients_.begin(); it != clients_.end();) {
    const std::int64_t silent_ns = now_ns - it->second.last_seen_ns;
    if (silent_ns > limits_.heartbeat_timeout_ns + limits_.client_grace_ns) {
      gone.push_back(it->first);
      const auto next = std::next(it);
      forget(it);
      it = next;
      ++counters_.expired_clients;
      continue;
    }
    if (silent_ns > limits_.heartbeat_timeout_ns && !it->second.suspended) {
      it->second.suspended = true;
      ++counters_.suspended_clients;
      changes_.push_back({it->first, false, silent_ns});
    }
    ++it;
  }
  if (!gone.empty()) recount();
  return gone;
}

bool SubscriptionTable::due(const Subscription& s, DeviceSchedule& d, double index) {
  if (d.next_due < 0.0) {
    d.next_due = index + s.period;
    // Latest-value streams start at once; a batch first collects a period's worth of samples.
    return s.kind != StreamKind::ContactBatch;
  }
  if (index + 1e-9 < d.next_due) return false;
  d.next_due += s.period;
  if (d.next_due <= index) d.next_due = index + s.period;  // far behind (a gap): no burst
  return true;
}

void SubscriptionTable::sendBatch(const Subscription& s, DeviceSchedule& d, std::int64_t now_us, MessageSink& sink) {
  thx_msgs::contact_batch_t& b = d.batch;
  b.utime = now_us;
  ++b.seq;
  b.next_tick = d.next_tick;
  b.num_samples = std::int32_t(b.samples.size());
  sink.sendTo(s.data_port, s.channel, b);
  b.samples.clear();  // keeps its capacity
  b.num_dropped = 0;
}

void SubscriptionTable::sendDeviceState(const Subscription& s, DeviceSchedule& d,
                                        const thx_msgs::device_state_t& state, MessageSink& sink) {
  d.flags_seen |= state.flags_seen;
  d.fault_mask |= state.fault_mask;
  if (!due(s, d, double(state.tick))) return;
  thx_msgs::device_state_t out = state;  // fixed size: a copy, no allocation
  out.flags_seen = d.flags_seen;
  out.fault_mask = d.fault_mask;
  sink.sendTo(s.data_port, s.channel, out);
  d.flags_seen = 0;
  d.fault_mask = 0;
}

void SubscriptionTable::addSample(const Subscription& s, DeviceSchedule& d, std::int64_t tick,
                                  const thx_msgs::contact_t& contact, std::int64_t now_us, MessageSink& sink) {
  if (d.next_tick >= 0 && tick < d.next_tick) return;  // not newer: never sent twice
  if (d.next_tick >= 0 && tick > d.next_tick) d.batch.num_dropped += std::int32_t(tick - d.next_tick);
  d.batch.samples.push_back(contact);  // within the capacity reserved at subscription time
  d.next_tick = tick + 1;
  ++counters_.batch_samples;
  const bool on_time = due(s, d, double(tick));
  if (on_time || d.batch.samples.size() >= s.max_samples) sendBatch(s, d, now_us, sink);
}

bool SubscriptionTable::served(std::int32_t device) {
  if (device >= 0 && device < limits_.devices) return true;
  ++counters_.foreign_device;
  return false;
}

void SubscriptionTable::onTick(const thx_msgs::device_state_t& state, const thx_msgs::contact_t& contact,
                               std::int64_t now_us, MessageSink& sink) {
  if (!served(state.device)) return;
  const auto device = std::size_t(state.device);
  for (auto& [id, client] : clients_) {
    for (auto& [stream, s] : client.subs) {
      DeviceSchedule& d = s.devices[device];
      switch (s.kind) {
        case StreamKind::DeviceState:
          sendDeviceState(s, d, state, sink);
          break;
        case StreamKind::Contact:
          if (due(s, d, double(state.tick))) sink.sendTo(s.data_port, s.channel, contact);
          break;
        case StreamKind::ContactBatch:
          addSample(s, d, state.tick, contact, now_us, sink);
          break;
        case StreamKind::ServoStats:
          break;
      }
    }
  }
}

void SubscriptionTable::onStats(thx_msgs::servo_stats_t stats, MessageSink& sink) {
  if (!served(stats.device)) return;
  const auto device = std::size_t(stats.device);
  stats.num_clients = numClients();
  stats.num_subscriptions = numSubscriptions();
  const double window = double(stats_windows_[device]++);
  for (auto& [id, client] : clients_) {
    for (auto& [stream, s] : client.subs) {
      if (s.kind == StreamKind::ServoStats && due(s, s.devices[device], window)) {
        sink.sendTo(s.data_port, s.channel, stats);
      }
    }
  }
}

void SubscriptionTable::flushBatches(std::int64_t now_us, MessageSink& sink) {
  for (auto& [id, client] : clients_) {
    for (auto& [stream, s] : client.subs) {
      if (s.kind != StreamKind::ContactBatch) continue;
      for (DeviceSchedule& d : s.devices) {
        if (!d.batch.samples.empty()) sendBatch(s, d, now_us, sink);
      }
    }
  }
}

int SubscriptionTable::numSubscriptions() const {
  int n = 0;
  for (const auto& [id, client] : clients_) n += int(client.subs.size());
  return n;
}

double SubscriptionTable::bandwidth() const {
  double total = 0.0;
  for (const auto& [id, client] : clients_) {
    for (const auto& [stream, s] : client.subs) total += s.bytes_per_s;
  }
  return total;
}

void SubscriptionTable::recount() {
  tick_subscriptions_ = 0;
  for (const auto& [id, client] : clients_) {
    for (const auto& [stream, s] : client.subs) tick_subscriptions_ += s.kind != StreamKind::ServoStats;
  }
}

}  // namespace thx::srv
