#include "server/publisher.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <lcm/lcm-cpp.hpp>
#include <random>
#include <thx_msgs/protocol.hpp>

#include "server/process_memory.hpp"
#include "server/realtime.hpp"
#include "server/safety.hpp"
#include "server/session_log.hpp"
#include "server/tick_messages.hpp"

namespace thx::srv {

namespace {

std::int64_t clockNs(clockid_t id) {
  timespec ts{};
  clock_gettime(id, &ts);
  return std::int64_t(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}
std::int64_t monotonicNs() { return clockNs(CLOCK_MONOTONIC); }

// hello_t.server_instance: random and non-zero, so a restarted server is always told apart.
std::int64_t drawServerInstance() {
  std::random_device rd;
  std::seed_seq seed{rd(), rd(), rd(), unsigned(clockNs(CLOCK_REALTIME)), unsigned(::getpid())};
  std::mt19937_64 gen(seed);
  std::int64_t id = 0;
  while (id == 0) id = std::int64_t(gen() >> 1);  // positive: reads the same in every language
  return id;
}

std::string hostName() {
  char buf[256] = {};
  if (gethostname(buf, sizeof buf - 1) != 0) return "unknown";
  return buf;
}

const char* kindName(const std::string& stream, bool batch) { return batch ? "CONTACT (batched)" : stream.c_str(); }

}  // namespace

// Encodes into the publisher's reusable buffer and publishes raw bytes (docs/messages.md §7.4.5).
class Publisher::LcmSink : public MessageSink {
 public:
  explicit LcmSink(Publisher& p) : p_(p) {}
  void send(const std::string& ch, const thx_msgs::device_state_t& m) override { put(ch, m); }
  void send(const std::string& ch, const thx_msgs::contact_t& m) override { put(ch, m); }
  void send(const std::string& ch, const thx_msgs::contact_batch_t& m) override {
    if (thx_msgs::batch_count_consistent(m)) put(ch, m);
  }
  void send(const std::string& ch, const thx_msgs::servo_stats_t& m) override { put(ch, m); }
  void sendTo(int port, const std::string& ch, const thx_msgs::device_state_t& m) override { put(ch, m, port); }
  void sendTo(int port, const std::string& ch, const thx_msgs::contact_t& m) override { put(ch, m, port); }
  void sendTo(int port, const std::string& ch, const thx_msgs::contact_batch_t& m) override {
    if (thx_msgs::batch_count_consistent(m)) put(ch, m, port);
  }
  void sendTo(int port, const std::string& ch, const thx_msgs::servo_stats_t& m) override { put(ch, m, port); }

  // data_port 0: the bus; otherwise the client's own port.
  template <class M>
  void put(const std::string& channel, const M& m, int data_port = 0) {
    if (!p_.lcm_) return;
    lcm::LCM* target = p_.dataLcm(data_port);
    const int size = m.getEncodedSize();
    if (p_.encode_buffer_.size() < std::size_t(size)) p_.encode_buffer_.resize(std::size_t(size));
    if (!target || m.encode(p_.encode_buffer_.data(), 0, size) != size ||
        target->publish(channel, p_.encode_buffer_.data(), unsigned(size)) != 0) {
      // Say so once (e.g. a tcpq:// server that is down); --stats-json counts the rest.
      if (p_.publish_errors_.fetch_add(1, std::memory_order_relaxed) == 0)
        std::fprintf(stderr,
                     "hapticd: warning: LCM publish failed on %s: the LCM transport is unreachable or refused the "
                     "message; clients get nothing until it recovers, the servo runs on (publish_errors counts them)\n",
                     channel.c_str());
      return;
    }
    p_.published_.fetch_add(1, std::memory_order_relaxed);
    p_.published_bytes_.fetch_add(std::uint64_t(size), std::memory_order_relaxed);
  }

 private:
  Publisher& p_;
};

Publisher::Publisher(std::vector<PublishedDevice> devices, lcm::LCM* lcm, const PublisherOptions& options)
    : lcm_(lcm),
      options_(options),
      server_instance_(drawServerInstance()),
      table_([&] {
        SubscriptionLimits l = options.limits;
        l.servo_rate_hz = options.servo_rate_hz;
        l.server_instance = server_instance_;
        l.devices = int(devices.size());  // the table refuses a count outside 1..16
        return l;
      }()),
      commands_(options.fault_resets, server_instance_, options.scene_loads) {
  devices_.reserve(devices.size());
  for (std::size_t i = 0; i < devices.size(); ++i) {
    Device& d = devices_.emplace_back(FlightDumpGate(options.flight_limits, 1.0 / options.servo_rate_hz));
    d.parts = std::move(devices[i]);
    d.index = int(i);
  }
  server_name_ = "hapticd@" + hostName();
  scene_name_ = options_.scene_name;
  texture_fingerprint_ = options_.texture_fingerprint;
  if (server_name_.size() >= thx_msgs::kMaxTextLength) server_name_.resize(thx_msgs::kMaxTextLength - 1);
  if (options_.device_name.size() >= thx_msgs::kMaxTextLength) options_.device_name.resize(thx_msgs::kMaxTextLength - 1);
  encode_buffer_.resize(thx_msgs::kLcmShortMessageMaxSize);  // the largest batch we send
  if (lcm_) inbox_.attach(*lcm_);
  if (lcm_ && options_.control_lcm) inbox_.attach(*options_.control_lcm);
  if (lcm_ && options_.data_bus && options_.data_port_first > 0) {
    ports_ = std::make_unique<DataPorts>(*options_.data_bus, options_.data_port_first, options_.data_port_last);
    table_.useDataPorts(ports_.get());
  }
}

lcm::LCM* Publisher::dataLcm(int port) {
  if (port == 0) return lcm_;
  auto it = data_lcms_.find(port);
  if (it != data_lcms_.end()) return it->second.get();
  // Never subscribed nor handled, so LCM opens no receive socket for it: hapticd does not wake
  // for its own data (docs/clients.md §6). Opened once, kept for the port's next client.
  auto l = std::make_unique<lcm::LCM>(ports_->url(port));
  if (!l->good()) {
    std::fprintf(stderr, "hapticd: warning: cannot open the data port %s: its client gets no stream\n",
                 ports_->url(port).c_str());
    l.reset();
  } else {
    data_ports_open_.fetch_add(1, std::memory_order_relaxed);
  }
  return data_lcms_.emplace(port, std::move(l)).first->second.get();
}

Publisher::~Publisher() {
  stop();
  inbox_.detach();
}

void Publisher::start() {
  start_ns_ = monotonicNs();
  start_unix_us_ = clockNs(CLOCK_REALTIME) / 1000;
  last_stats_ns_ = start_ns_;
  thread_ = std::thread([this] { run(); });
}

void Publisher::stop() {
  if (!thread_.joinable()) return;
  stop_.store(true);
  thread_.join();
}

PublisherCounters Publisher::counters() const {
  PublisherCounters c;
  c.records = records_.load();
  c.published = published_.load();
  c.publish_errors = publish_errors_.load();
  c.flight_dumps = flight_dumps_.load();
  c.flight_dumps_over_count = flight_over_count_.load();
  c.flight_dumps_over_rate = flight_over_rate_.load();
  c.published_bytes = published_bytes_.load();
  c.hellos = hellos_.load();
  c.requests = requests_.load();
  c.refused = refused_.load();
  c.expired_clients = expired_.load();
  c.control_undecodable = inbox_.undecodable();
  c.commands = commands_answered_.load();
  c.clients = clients_.load();
  c.subscriptions = subscriptions_.load();
  c.data_ports_open = data_ports_open_.load();
  c.fifo = fifo_.load();
  return c;
}

std::string Publisher::lastFlightDump() const {
  while (dump_lock_.exchange(true)) {
  }
  std::string copy_of = last_dump_;
  dump_lock_.store(false);
  return copy_of;
}

void Publisher::run() {
  if (options_.fifo_priority > 0) {
    RealtimeOptions rt;
    rt.priority = options_.fifo_priority;
    rt.lock_memory = false;  // the servo's mlockall covers the process
    fifo_ = makeThreadRealtime(rt).fifo;
  }
  for (;;) {
    const bool stopping = stop_.load();
    std::int64_t now = monotonicNs();
    if (lcm_ && now - last_hello_ns_ >= options_.hello_period_ns) publishHello(now);
    applyControl(now);
    answerLoads(now);
    drainInTickOrder(stopping, now);
    for (Device& d : devices_) dumpFlight(d);
    now = monotonicNs();
    if (now - last_stats_ns_ >= 1'000'000'000) publishStats(now);
    clients_.store(table_.numClients(), std::memory_order_relaxed);
    subscriptions_.store(table_.numSubscriptions(), std::memory_order_relaxed);
    if (stopping) {
      LcmSink sink(*this);
      table_.flushBatches(now / 1000, sink);
      break;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
}

// The devices' records merged by tick (a tick's devices in index order), so the session log and
// the streams see them in tick order. The group pushes member 0's record, then member 1's, ... so
// a device's record of a tick may not be in its ring yet while another's is: a record goes out
// only once every device has one waiting (the earliest first), or at the stop, when the rings
// hold all there will be.
void Publisher::drainInTickOrder(bool stopping, std::int64_t now_ns) {
  for (;;) {
    for (Device& d : devices_) {
      if (!d.waiting && d.parts.ring->pop(d.next)) d.waiting = true;
    }
    Device* earliest = nullptr;
    bool every = true;
    for (Device& d : devices_) {
      if (!d.waiting) {
        every = false;
      } else if (!earliest || d.next.tick < earliest->next.tick) {
        earliest = &d;
      }
    }
    if (!earliest || (!every && !stopping)) return;
    earliest->waiting = false;
    handleRecord(*earliest, earliest->next, now_ns);
  }
}

void Publisher::applyControl(std::int64_t now_ns) {
  inbox_.take(control_);
  LcmSink sink(*this);
  for (const auto& hb : control_.heartbeats) table_.heartbeat(hb.msg, hb.received_ns);
  for (const auto& req : control_.requests) {
    thx_msgs::subscribe_reply_t reply = table_.handleRequest(req.msg, req.received_ns);
    reply.utime = now_ns / 1000;
    requests_.fetch_add(1, std::memory_order_relaxed);
    if (!reply.accepted) refused_.fetch_add(1, std::memory_order_relaxed);
    sink.put(thx_msgs::kChannelSubscribeReply, reply);
    if (!options_.log_subscriptions) continue;
    const bool sub = req.msg.action == thx_msgs::subscribe_request_t::ACTION_SUBSCRIBE;
    if (!reply.accepted) {
      std::fprintf(stderr, "hapticd: refused %s of client %s: %s\n", sub ? "a subscription" : "a request",
                   reply.client_id.c_str(), reply.reason.c_str());
    } else if (sub) {
      std::fprintf(stderr, "hapticd: client %s: %s at %g Hz on %s%s%s%s%s\n", reply.client_id.c_str(),
                   kindName(reply.stream, reply.batch), reply.rate_hz, reply.channel.c_str(),
                   reply.data_url.empty() ? "" : " at ", reply.data_url.c_str(), reply.reason.empty() ? "" : "; ",
                   reply.reason.c_str());
    } else {
      std::fprintf(stderr, "hapticd: client %s: %s unsubscribed\n", reply.client_id.c_str(), reply.stream.c_str());
    }
  }
  for (const auto& cmd : control_.commands) {
    if (auto refused = commands_.handle(cmd.msg)) {
      refused->utime = now_ns / 1000;
      sink.put(thx_msgs::kChannelCommandReply, *refused);
      commands_answered_.fetch_add(1, std::memory_order_relaxed);
      if (options_.log_subscriptions) {
        std::fprintf(stderr, "hapticd: refused a command of client %s: %s\n", refused->client_id.c_str(),
                     refused->reason.c_str());
      }
    }
  }
  const std::vector<std::string> forgotten = table_.expire(now_ns);
  if (options_.log_subscriptions) {
    for (const SubscriptionTable::ClientChange& c : table_.takeChanges()) {
      if (c.back) {
        std::fprintf(stderr, "hapticd: client %s is back after %.3g s of silence: served as before\n",
                     c.client_id.c_str(), double(c.silent_ns) * 1e-9);
      } else {
        std::fprintf(stderr, "hapticd: client %s: no heartbeat for %.3g s; its streams and port are kept %.3g s more\n",
                     c.client_id.c_str(), double(options_.limits.heartbeat_timeout_ns) * 1e-9,
                     double(options_.limits.client_grace_ns) * 1e-9);
      }
    }
  } else {
    table_.takeChanges();
  }
  for (const std::string& id : forgotten) {
    expired_.fetch_add(1, std::memory_order_relaxed);
    if (options_.log_subscriptions) {
      std::fprintf(stderr, "hapticd: client %s forgotten: no heartbeat for %.3g s\n", id.c_str(),
                   double(options_.limits.heartbeat_timeout_ns + options_.limits.client_grace_ns) * 1e-9);
    }
  }
}

void Publisher::handleRecord(Device& device, const TickRecord& r, std::int64_t now_ns) {
  records_.fetch_add(1, std::memory_order_relaxed);
  // Commands first: a switch device 0's record shows is recorded as a hello before this tick.
  if (device.index == 0) answerCommands(r, now_ns);
  if (SessionRecorder* s = options_.session; s && s->ok()) {
    if (session_hello_due_) s->recordHello(hello(r.deadline_ns / 1000));  // on the ticks' clock
    session_hello_due_ = false;
    s->record(r, device.index);
    if (!s->ok()) std::fprintf(stderr, "hapticd: warning: %s\n", s->error().c_str());
  }
  ++device.ticks_seen;
  device.missed_seen += std::uint64_t(r.missed);
  if (r.missed > device.window_max_missed) device.window_max_missed = r.missed;
  if (r.safety_flags & kSafetyClampMask) ++device.window_clamped;
  if (r.faults) {
    ++device.fault_ticks_seen;
    ++device.window_fault_ticks;
    device.window_fault_mask |= wireFaultMask(r.faults);
  }
  const double f = std::sqrt(r.f_out[0] * r.f_out[0] + r.f_out[1] * r.f_out[1] + r.f_out[2] * r.f_out[2]);
  if (f > device.window_max_force_n) device.window_max_force_n = f;
  if (!lcm_ || !table_.wantsTicks()) return;  // compute a stream only while someone subscribes
  thx_msgs::device_state_t d{};
  thx_msgs::contact_t c{};
  toDeviceState(r, device.parts.simulated, d);
  toContact(r, c);
  d.device = device.index;
  c.device = device.index;
  LcmSink sink(*this);
  table_.onTick(d, c, now_ns / 1000, sink);
}

// A fault reset or a scene switch is answered by the first record that shows the servo applied
// it; a new scene is announced at once.
void Publisher::answerCommands(const TickRecord& r, std::int64_t now_ns) {
  if (commands_.pending() == 0) return;
  command_replies_.clear();
  commands_.onRecord(r, command_replies_);
  sendReplies(now_ns);
  if (std::optional<ServerCommands::SceneChange> change = commands_.takeSceneChange()) {
    scene_name_ = std::move(change->scene_name);
    if (scene_name_.size() >= thx_msgs::kMaxTextLength) scene_name_.resize(thx_msgs::kMaxTextLength - 1);
    texture_fingerprint_ = change->fingerprint;
    session_hello_due_ = true;
    if (lcm_) publishHello(now_ns);
  }
}

// A scene load that failed is answered as soon as the loader knows.
void Publisher::answerLoads(std::int64_t now_ns) {
  if (commands_.pending() == 0) return;
  command_replies_.clear();
  commands_.pollLoads(command_replies_);
  sendReplies(now_ns);
}

void Publisher::sendReplies(std::int64_t now_ns) {
  LcmSink sink(*this);
  for (thx_msgs::server_command_reply_t& reply : command_replies_) {
    reply.utime = now_ns / 1000;
    sink.put(thx_msgs::kChannelCommandReply, reply);
    commands_answered_.fetch_add(1, std::memory_order_relaxed);
    if (!options_.log_subscriptions) continue;
    if (!reply.accepted) {
      std::fprintf(stderr, "hapticd: refused a command of client %s: %s\n", reply.client_id.c_str(), reply.reason.c_str());
    } else if (reply.action == thx_msgs::server_command_t::ACTION_LOAD_SCENE) {
      std::fprintf(stderr, "hapticd: client %s switched the scene; the servo renders it from tick %lld\n",
                   reply.client_id.c_str(), (long long)reply.tick);
    } else {
      std::fprintf(stderr, "hapticd: client %s reset the latched fault at tick %lld\n", reply.client_id.c_str(),
                   (long long)reply.tick);
    }
  }
}

void Publisher::publishStats(std::int64_t now_ns) {
  const double window_s = double(now_ns - last_stats_ns_) * 1e-9;
  for (Device& d : devices_) publishStats(d, window_s, now_ns);
  last_stats_ns_ = now_ns;
}

void Publisher::publishStats(Device& d, double window_s, std::int64_t now_ns) {
  const std::uint64_t ticks = d.ticks_seen, missed = d.missed_seen;
  if (lcm_) {
    thx_msgs::servo_stats_t s{};
    s.utime = now_ns / 1000;
    s.ticks = std::int64_t(ticks);
    s.missed_ticks = std::int64_t(missed);
    s.window_ticks = std::int64_t(ticks - d.last_stats_ticks);
    s.window_missed_ticks = std::int64_t(missed - d.last_stats_missed);
    s.window_max_consecutive_missed = d.window_max_missed;
    s.window_clamped_ticks = d.window_clamped;
    s.window_s = window_s;
    s.rate_nominal_hz = options_.servo_rate_hz;
    s.rate_hz = window_s > 0 ? double(s.window_ticks) / window_s : 0.0;
    const LatencyHistogram& c = d.parts.servo->computeHistogram();
    const LatencyHistogram& w = d.parts.servo->wakeHistogram();
    s.compute_p50_us = c.quantileUs(0.5);
    s.compute_p99_us = c.quantileUs(0.99);
    s.compute_p999_us = c.quantileUs(0.999);
    s.compute_max_us = double(c.maxNs()) / 1e3;
    s.wake_p50_us = w.quantileUs(0.5);
    s.wake_p99_us = w.quantileUs(0.99);
    s.wake_p999_us = w.quantileUs(0.999);
    s.wake_max_us = double(w.maxNs()) / 1e3;
    s.f_max = d.window_max_force_n;
    s.snapshots_dropped = std::int64_t(d.parts.ring->dropped());
    s.rss_bytes = readProcessMemory().rss_bytes;
    s.fault_ticks = std::int64_t(d.fault_ticks_seen);
    s.window_fault_ticks = d.window_fault_ticks;
    s.window_fault_mask = d.window_fault_mask;
    s.device = d.index;
    LcmSink sink(*this);
    table_.onStats(s, sink);
  }
  d.last_stats_ticks = ticks;
  d.last_stats_missed = missed;
  d.window_max_force_n = 0.0;
  d.window_max_missed = 0;
  d.window_clamped = 0;
  d.window_fault_ticks = 0;
  d.window_fault_mask = 0;
}

thx_msgs::hello_t Publisher::hello(std::int64_t utime) const {
  thx_msgs::hello_t h{};
  h.utime = utime;
  h.seq = hello_seq_;
  h.server_instance = server_instance_;
  h.start_utime = start_ns_ / 1000;
  h.start_unix_us = start_unix_us_;
  h.protocol_version = thx_msgs::hello_t::PROTOCOL_VERSION;
  h.servo_rate_hz = options_.servo_rate_hz;
  h.server_name = server_name_;
  h.device = options_.device_name;
  h.scene_name = scene_name_;
  h.texture_fingerprint = static_cast<std::int64_t>(texture_fingerprint_);  // the same 64 bits
  h.control_url = options_.control_url;
  h.device_names = options_.device_names;
  return h;
}

void Publisher::publishHello(std::int64_t now_ns) {
  ++hello_seq_;
  const thx_msgs::hello_t h = hello(now_ns / 1000);
  LcmSink sink(*this);
  sink.put(thx_msgs::kChannelHello, h);
  hellos_.fetch_add(1, std::memory_order_relaxed);
  last_hello_ns_ = now_ns;
}

void Publisher::dumpFlight(Device& device) {
  try {
    const FlightDump d =
        dumpWithinLimits(*device.parts.recorder, device.flight_gate, options_.flight_dir, device.parts.flight_tag);
    if (d.outcome == FlightDumpOutcome::OverRate) flight_over_rate_.fetch_add(1);
    if (d.outcome == FlightDumpOutcome::OverCount && flight_over_count_.fetch_add(1) == 0) {
      std::fprintf(stderr,
                   "hapticd: fault: %llu flight records written to %s, the most one run writes (--flight-max); "
                   "further faults are counted, not written\n",
                   (unsigned long long)device.flight_gate.limits().max_files, options_.flight_dir.c_str());
    }
    if (d.outcome != FlightDumpOutcome::Written) return;
    flight_dumps_.fetch_add(1);
    while (dump_lock_.exchange(true)) {
    }
    last_dump_ = d.path;
    dump_lock_.store(false);
    std::fprintf(stderr, "hapticd: fault: flight record written to %s\n", d.path.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hapticd: %s\n", e.what());
  }
}

}  // namespace thx::srv
