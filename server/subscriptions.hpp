#pragma once
// Per-client subscriptions of hapticd (docs/clients.md, protocol in docs/messages.md §4): which
// client gets which stream, on which channel, at which rate, and when. Pure bookkeeping: no LCM,
// no threads, no clock of its own. Time comes in as arguments (ns on any monotonic clock, used
// only for heartbeats), and rates are scheduled on the servo's tick count, so tests drive it
// deterministically. The publisher thread owns one table; nothing here runs on the servo.
//
// Rates are granted as asked (within the limits) and met on average: a subscription at R Hz is
// sent the latest tick whenever the tick count passes its next due point, which advances by
// servo_rate / R ticks (a fraction), so 60 Hz of 1 kHz alternates 17- and 16-tick intervals.
// A DEVICE_STATE message also carries what the ticks it skipped saw: its flags_seen and
// fault_mask are OR-ed over every tick since the previous message to that subscriber, so a
// one-tick fault reaches a 60 Hz client.
//
// Several devices (protocol 6, issue 30): the publisher hands the table every device's ticks and
// stats windows, each message carrying its `device` index. A subscription is one grant on one
// channel, but its schedule is kept per device: at R Hz it gets R Hz of EACH device's messages,
// each tagged with its device, with flags_seen/fault_mask OR-ed over that device's ticks only, and
// for CONTACT batches one batch per device (its `device` set, its own next_tick, num_dropped and
// seq, so a client detects gaps per device). A record of a device the server does not serve is
// not sent (counted in foreign_device). Its bandwidth estimate is therefore `devices` times one
// device's (streamBandwidth), and that is what the bandwidth limit weighs.
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <thx_msgs/contact_batch_t.hpp>
#include <thx_msgs/contact_t.hpp>
#include <thx_msgs/device_state_t.hpp>
#include <thx_msgs/heartbeat_t.hpp>
#include <thx_msgs/servo_stats_t.hpp>
#include <thx_msgs/subscribe_reply_t.hpp>
#include <thx_msgs/subscribe_request_t.hpp>

#include "server/data_ports.hpp"

namespace thx::srv {

struct SubscriptionLimits {
  double servo_rate_hz = 1000.0;
  double max_rate_hz = 1000.0;              // per subscription; higher asks are granted this
  int max_clients = 32;                     // clients with at least one subscription
  double max_bandwidth_bytes_per_s = 8e6;   // sum of the estimates below over all subscriptions
  std::int64_t heartbeat_timeout_ns = 2'000'000'000;
  // A client silent past the heartbeat timeout is suspended for this long more before it is
  // forgotten (docs/clients.md §6, "A pulled cable"): its grants, data port and batch sequence stay and its streams
  // keep flowing, so a cable pulled and put back within the grace is served again as soon as
  // packets pass, with nothing to ask again. A heartbeat or request resumes it. 0: forgotten at
  // the timeout.
  std::int64_t client_grace_ns = 10'000'000'000;
  double stats_window_s = 1.0;              // SERVO_STATS is computed per window: at most 1/window Hz
  std::int64_t server_instance = 1;         // echoed in replies and batches
  int devices = 1;                          // devices served (1..kMaxDevices), indices 0..devices-1
  static constexpr int kMaxDevices = 16;
};

enum class StreamKind { DeviceState, Contact, ContactBatch, ServoStats };

// Where the messages go. The publisher encodes and publishes; tests record.
class MessageSink {
 public:
  virtual ~MessageSink() = default;
  virtual void send(const std::string& channel, const thx_msgs::device_state_t& m) = 0;
  virtual void send(const std::string& channel, const thx_msgs::contact_t& m) = 0;
  virtual void send(const std::string& channel, const thx_msgs::contact_batch_t& m) = 0;
  virtual void send(const std::string& channel, const thx_msgs::servo_stats_t& m) = 0;
  // The table sends through these: `data_port` is the client's own udpm port (DataPorts), 0 for
  // the bus. A sink that has no ports (tests) keeps the default, which ignores it.
  virtual void sendTo(int data_port, const std::string& channel, const thx_msgs::device_state_t& m) {
    (void)data_port;
    send(channel, m);
  }
  virtual void sendTo(int data_port, const std::string& channel, const thx_msgs::contact_t& m) {
    (void)data_port;
    send(channel, m);
  }
  virtual void sendTo(int data_port, const std::string& channel, const thx_msgs::contact_batch_t& m) {
    (void)data_port;
    send(channel, m);
  }
  virtual void sendTo(int data_port, const std::string& channel, const thx_msgs::servo_stats_t& m) {
    (void)data_port;
    send(channel, m);
  }
};

struct SubscriptionCounters {
  std::uint64_t requests = 0;
  std::uint64_t refused = 0;
  std::uint64_t heartbeats = 0;
  std::uint64_t unknown_heartbeats = 0;  // from a client with no subscription (e.g. after a restart)
  std::uint64_t expired_clients = 0;
  std::uint64_t suspended_clients = 0;   // silent past the heartbeat timeout, within the grace
  std::uint64_t resumed_clients = 0;     // heard from again while suspended
  std::uint64_t batch_samples = 0;
  std::uint64_t foreign_device = 0;      // ticks and stats windows of a device index not served: not sent
};

// Bytes per second one subscription puts on the wire (LCM payload + channel + LCM's 8-byte
// header; IP/UDP headers not counted), of one device: the table weighs `devices` times this
// against the bandwidth limit.
double streamBandwidth(StreamKind kind, double rate_hz, double servo_rate_hz, std::size_t channel_length);

class SubscriptionTable {
 public:
  // Throws thx::Error (Config) when limits.devices is outside 1..kMaxDevices.
  explicit SubscriptionTable(const SubscriptionLimits& limits);
  // From now on each client gets a data port of its own from `ports` with its first grant (a
  // new client is refused when none is free), named in the reply's data_url, and gives it back
  // when it leaves or expires. Without (the default, or null): every stream on the bus, data_url "".
  // Not owned; call before the first request.
  void useDataPorts(DataPorts* ports) { ports_ = ports; }

  // Applies a request and returns the reply to publish (utime left 0 for the caller).
  // Refusals change nothing. A request also counts as a sign of life of its client.
  thx_msgs::subscribe_reply_t handleRequest(const thx_msgs::subscribe_request_t& req, std::int64_t now_ns);
  // Returns false when the client is unknown (no subscriptions); the heartbeat is then ignored.
  bool heartbeat(const thx_msgs::heartbeat_t& hb, std::int64_t now_ns);
  // Suspends clients silent for longer than the heartbeat timeout, and forgets those silent for
  // longer than the timeout and the grace; returns the forgotten ids.
  std::vector<std::string> expire(std::int64_t now_ns);
  // A client suspended (silent past the heartbeat timeout) or back (heard from while suspended),
  // with how long it had been silent: what changed since the last call, for hapticd's log.
  struct ClientChange {
    std::string client_id;
    bool back = false;
    std::int64_t silent_ns = 0;
  };
  std::vector<ClientChange> takeChanges();

  // True when some subscription needs per-tick data (DEVICE_STATE, CONTACT, CONTACT batch):
  // the publisher builds the tick's messages only then.
  bool wantsTicks() const { return tick_subscriptions_ > 0; }
  // One servo tick of device `state.device` (contact.device is the same), in tick order for that
  // device. `tick` gaps (ring overflow) count as dropped samples in that device's batches. Sends
  // what is due to `sink`.
  void onTick(const thx_msgs::device_state_t& state, const thx_msgs::contact_t& contact, std::int64_t now_us,
              MessageSink& sink);
  // One closed SERVO_STATS window of device `stats.device`. num_clients/num_subscriptions are
  // filled in here.
  void onStats(thx_msgs::servo_stats_t stats, MessageSink& sink);
  // Sends every device's batch's remaining samples (at shutdown).
  void flushBatches(std::int64_t now_us, MessageSink& sink);

  int numClients() const { return int(clients_.size()); }
  int numSubscriptions() const;
  double bandwidth() const;  // bytes/s, current total estimate
  const SubscriptionCounters& counters() const { return counters_; }
  const SubscriptionLimits& limits() const { return limits_; }

 private:
  // What a subscription schedules for one device: every device runs its own ticks and windows.
  struct DeviceSchedule {
    double next_due = -1.0;  // < 0: send at the first opportunity
    // DEVICE_STATE only: flags_seen and fault_mask of this device's ticks since its last message
    std::int32_t flags_seen = 0;
    std::int32_t fault_mask = 0;
    // batches only
    thx_msgs::contact_batch_t batch{};  // value-initialised: lcm-gen structs have no member initialisers
    std::int64_t next_tick = -1;        // tick expected next; -1 before the first
  };
  struct Subscription {
    StreamKind kind = StreamKind::DeviceState;
    std::string channel;
    double rate_hz = 0.0;
    double period = 1.0;  // ticks (stats: windows) between messages
    double bytes_per_s = 0.0;
    std::size_t max_samples = 0;  // batches only
    int data_port = 0;            // the client's (DataPorts); 0: the bus
    // One per device, sized once at subscription time (a batch holds its samples' capacity, so a
    // fixed array of kMaxDevices would cost 16 batches per subscription).
    std::vector<DeviceSchedule> devices;
  };
  struct Client {
    std::int64_t last_seen_ns = 0;
    bool suspended = false;
    int data_port = 0;                         // DataPorts; 0: the bus
    std::map<std::string, Subscription> subs;  // by stream name
  };
  void forget(std::map<std::string, Client>::iterator it);  // erases, and frees its data port
  void heardFrom(Client& client, const std::string& id, std::int64_t now_ns);
  // A batch subscription's sequences (one per device) outlive it: a client that subscribes again
  // on the same channel (after being forgotten, or unsubscribing) continues them, so what it
  // receives after the gap counts as new (docs/messages.md, contact_batch_t). Bounded: the map is
  // cleared when it would hold more than kMaxRetiredChannels channels' worth of sequences.
  void retire(const Subscription& s);
  static constexpr std::size_t kMaxRetiredChannels = 4096;
  bool served(std::int32_t device);  // false (and counted in foreign_device) when not

  thx_msgs::subscribe_reply_t refuse(thx_msgs::subscribe_reply_t reply, std::string reason);
  static bool due(const Subscription& s, DeviceSchedule& d, double index);
  static void sendDeviceState(const Subscription& s, DeviceSchedule& d, const thx_msgs::device_state_t& state,
                              MessageSink& sink);
  // A tick's sample into the device's batch; sends the batch when due or full.
  void addSample(const Subscription& s, DeviceSchedule& d, std::int64_t tick, const thx_msgs::contact_t& contact,
                 std::int64_t now_us, MessageSink& sink);
  static void sendBatch(const Subscription& s, DeviceSchedule& d, std::int64_t now_us, MessageSink& sink);
  void recount();

  SubscriptionLimits limits_;
  DataPorts* ports_ = nullptr;
  std::map<std::string, Client> clients_;
  std::map<std::pair<std::string, int>, std::int64_t> retired_batch_seq_;  // by (channel, device)
  std::vector<ClientChange> changes_;
  int tick_subscriptions_ = 0;
  std::vector<std::int64_t> stats_windows_;  // per device: windows seen so far
  SubscriptionCounters counters_;
};

}  // namespace thx::srv
