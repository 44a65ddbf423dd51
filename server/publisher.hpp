#pragma once
// The publisher thread: everything that leaves hapticd over LCM, and the flight-record dumps.
// It drains the servo's tick ring (the servo never waits for it), applies subscription requests
// and heartbeats (queued by the receiver thread, server/subscription_inbox.hpp) to its
// SubscriptionTable, publishes each subscribed stream to its client on the client's own channel
// at the client's rate (docs/clients.md), answers requests on THX_SUBSCRIBE_REPLY and commands on
// THX_COMMAND_REPLY (server/server_commands.hpp), announces the
// server on THX_HELLO once per second and at once when a client switched the scene, closes a SERVO_STATS window once per second, and writes
// frozen flight records to files. Nothing is encoded for a stream nobody subscribes to.
//
// Several devices (issue 30): it drains every device's ring, each record's messages carry the
// device's index (protocol 6), a subscription gets each device's messages at its rate
// (subscriptions.hpp), each device has its own SERVO_STATS window and flight-record limits, and
// its flight records are named after it. Commands are answered from device 0's records.
//
// There is no broadcast: every data message goes to a subscriber's channel.
#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <thx_msgs/hello_t.hpp>

#include "server/flight_dump_limits.hpp"
#include "server/flight_recorder.hpp"
#include "server/server_commands.hpp"
#include "server/servo.hpp"
#include "rt/spsc_ring.hpp"
#include "server/subscription_inbox.hpp"
#include "server/subscriptions.hpp"
#include "server/tick_record.hpp"
#include "server/udpm_url.hpp"

namespace lcm {
class LCM;
}

namespace thx::srv {

class SessionRecorder;

struct PublisherOptions {
  double servo_rate_hz = 1000.0;
  std::string flight_dir = ".";
  FlightDumpLimits flight_limits;  // --flight-max, --flight-interval (server/flight_dump_limits.hpp)
  bool simulated_device = false;  // the one device's (the one-device constructor); else PublishedDevice's
  std::string device_name = "sim";  // hello_t.device
  // hello_t.device_names: the devices' names, comma-separated in index order (the scene's
  // `device`: Phantom0; a `devices:` list: its names).
  std::string device_names = "Phantom0";
  std::string scene_name;           // hello_t.scene_name (scene::sceneName)
  std::uint64_t texture_fingerprint = 0;  // hello_t.texture_fingerprint (scene::SceneSurface)
  bool log_subscriptions = false;    // one stderr line per subscription change, refusal, expiry
  // Client limits. servo_rate_hz and server_instance are set by the publisher.
  SubscriptionLimits limits;
  std::int64_t hello_period_ns = 1'000'000'000;
  // Every tick that comes out of the ring is also written here (hapticd --record), and a hello
  // before the first tick and before the first tick on each switched-to scene; not owned.
  SessionRecorder* session = nullptr;
  // Every device's Servo::faultResetSlot(), written only by the publisher thread (client fault
  // resets clear every device's latch: server_commands.hpp); empty: resets are refused. Not owned.
  std::vector<rt::LatestSlot<FaultReset>*> fault_resets;
  // Loads scenes for client switches (server/scene_switcher.hpp), used only by the publisher
  // thread; null: switches are refused. Not owned.
  SceneLoads* scene_loads = nullptr;
  // Each client's streams on a udpm port of its own (issue 17, docs/clients.md §6): ports
  // data_port_first..data_port_last on data_bus's group and query (hapticd --data-ports), named in
  // subscribe_reply_t.data_url and published through send-only LCMs, one per port, opened on first
  // use and kept. Unset: every stream on the bus LCM, data_url "".
  std::optional<UdpmUrl> data_bus;
  int data_port_first = 0, data_port_last = 0;
  // hello_t.control_url: where clients send requests, heartbeats, commands and forces
  // (hapticd --control-port); "" = the bus. The publisher's inbox also listens on control_lcm,
  // hapticd's LCM on that URL (handled by the receiver thread). Not owned; may be null.
  std::string control_url;
  lcm::LCM* control_lcm = nullptr;
  // > 0: the publisher thread asks for SCHED_FIFO at this priority (below the servo's 80; hapticd
  // --io-priority). Every client's streams pass through this one thread: descheduled behind 64
  // clients and other work on two cores it stalled for ~0.4 s, and every client lost the same
  // ticks (issue 17). Refused without the privilege; the thread then runs as before.
  int fifo_priority = 0;
};

struct PublisherCounters {
  std::uint64_t records = 0;
  std::uint64_t published = 0;  // every LCM message sent (streams, replies, hellos)
  std::uint64_t publish_errors = 0;
  std::uint64_t flight_dumps = 0;
  std::uint64_t flight_dumps_over_count = 0;  // faults not written: the file cap was reached
  std::uint64_t flight_dumps_over_rate = 0;   // faults not written: too soon after the last file
  std::uint64_t published_bytes = 0;
  std::uint64_t hellos = 0;
  std::uint64_t requests = 0;
  std::uint64_t refused = 0;
  std::uint64_t expired_clients = 0;
  std::uint64_t control_undecodable = 0;  // THX_SUBSCRIBE / THX_HEARTBEAT / THX_COMMAND bytes try_decode refused
  std::uint64_t commands = 0;             // server_command_t answered (accepted or refused)
  int clients = 0;                        // now
  int subscriptions = 0;                  // now
  int data_ports_open = 0;                // send-only LCMs opened for data ports so far
  bool fifo = false;                      // the publisher thread runs SCHED_FIFO (fifo_priority)
};

// One device the publisher serves. Not owned; each outlives the publisher.
struct PublishedDevice {
  rt::SpscRing<TickRecord>* ring = nullptr;  // its servo's tick ring (ServoRig::ring())
  const Servo* servo = nullptr;              // its latency histograms, for SERVO_STATS
  FlightRecorder* recorder = nullptr;        // its flight record
  // Its flight-record files are named flight-<flight_tag>-tick...; "" (one device): flight-tick...
  std::string flight_tag;
  bool simulated = false;  // device_state_t's simulated flag for its messages
};

class Publisher {
 public:
  // lcm may be null (no transport): records are still drained and flight records still dumped.
  // With lcm, the publisher subscribes to THX_SUBSCRIBE, THX_HEARTBEAT and THX_COMMAND on it; whoever calls
  // lcm->handle() (hapticd's receiver thread) delivers them.
  // `devices`: 1 to 16, device i's messages carrying index i.
  Publisher(std::vector<PublishedDevice> devices, lcm::LCM* lcm, const PublisherOptions& options);
  // One device.
  Publisher(rt::SpscRing<TickRecord>& ring, const Servo& servo, FlightRecorder& recorder, lcm::LCM* lcm,
            const PublisherOptions& options)
      : Publisher(std::vector<PublishedDevice>{{&ring, &servo, &recorder, "", options.simulated_device}}, lcm,
                  options) {}
  ~Publisher();

  void start();
  void stop();  // drains what is left, flushes batches, then joins

  PublisherCounters counters() const;
  std::string lastFlightDump() const;
  std::int64_t serverInstance() const { return server_instance_; }

 private:
  class LcmSink;
  void run();
  void applyControl(std::int64_t now_ns);
  struct Device;
  void drainInTickOrder(bool stopping, std::int64_t now_ns);
  void handleRecord(Device& device, const TickRecord& r, std::int64_t now_ns);
  void answerCommands(const TickRecord& r, std::int64_t now_ns);
  void answerLoads(std::int64_t now_ns);
  void sendReplies(std::int64_t now_ns);  // command_replies_
  void publishStats(std::int64_t now_ns);
  void publishStats(Device& device, double window_s, std::int64_t now_ns);
  void publishHello(std::int64_t now_ns);
  thx_msgs::hello_t hello(std::int64_t utime) const;  // the announcement of the scene rendered now
  void dumpFlight(Device& device);
  lcm::LCM* dataLcm(int port);  // port 0: lcm_; else the port's send-only LCM (null if it cannot open)

  // What the publisher keeps per device; the counters and windows are the publisher thread's.
  struct Device {
    explicit Device(FlightDumpGate gate) : flight_gate(std::move(gate)) {}
    PublishedDevice parts;
    int index = 0;
    FlightDumpGate flight_gate;  // each device's faults are limited on their own
    TickRecord next;             // popped from its ring, not handled yet (drainInTickOrder)
    bool waiting = false;
    std::uint64_t ticks_seen = 0;   // counted from the records: the servo's own counters are
    std::uint64_t missed_seen = 0;  // not shared across threads
    std::uint64_t last_stats_ticks = 0;
    std::uint64_t last_stats_missed = 0;
    double window_max_force_n = 0.0;
    std::int32_t window_max_missed = 0;
    std::int32_t window_clamped = 0;
    std::uint64_t fault_ticks_seen = 0;
    std::int32_t window_fault_ticks = 0;
    std::int32_t window_fault_mask = 0;
  };
  std::vector<Device> devices_;
  lcm::LCM* lcm_;
  PublisherOptions options_;
  std::int64_t server_instance_ = 0;
  std::int64_t start_ns_ = 0, start_unix_us_ = 0;
  std::string server_name_;
  std::string scene_name_;               // hello_t: the scene the servo renders now
  std::uint64_t texture_fingerprint_ = 0;
  std::unique_ptr<DataPorts> ports_;                  // null: streams on the bus
  std::map<int, std::unique_ptr<lcm::LCM>> data_lcms_;  // by port; publish only, never subscribed
  std::atomic<int> data_ports_open_{0};
  std::atomic<bool> fifo_{false};  // the thread got SCHED_FIFO (fifo_priority)
  SubscriptionTable table_;
  SubscriptionInbox inbox_;
  ServerCommands commands_;
  std::vector<thx_msgs::server_command_reply_t> command_replies_;  // reused
  ControlMessages control_;                  // reused every loop
  std::vector<std::uint8_t> encode_buffer_;  // reused for every message
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::int64_t last_stats_ns_ = 0;
  std::int64_t last_hello_ns_ = 0;
  std::int64_t hello_seq_ = 0;
  bool session_hello_due_ = true;  // --record: a hello goes before the next tick (at start, after a switch)
  std::atomic<std::uint64_t> commands_answered_{0};
  std::atomic<std::uint64_t> records_{0}, published_{0}, publish_errors_{0}, flight_dumps_{0}, published_bytes_{0},
      hellos_{0}, requests_{0}, refused_{0}, expired_{0};
  std::atomic<int> clients_{0}, subscriptions_{0};
  std::atomic<std::uint64_t> flight_over_count_{0}, flight_over_rate_{0};
  mutable std::atomic<bool> dump_lock_{false};
  std::string last_dump_;
};

}  // namespace thx::srv
