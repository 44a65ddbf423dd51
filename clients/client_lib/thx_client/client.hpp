#pragma once
// thx_client: what every client of hapticd uses to get its streams (docs/clients.md).
//
//   lcm::LCM lcm(thx_msgs::kDefaultLcmUrl);
//   thx::client::Client c(lcm, "visual");
//   c.subscribe(thx_msgs::Stream::DeviceState, 60.0);
//   for (;;) { c.poll(5); if (auto s = c.latestDeviceState()) draw(*s); }
//
// The client asks for its streams on THX_SUBSCRIBE, resends unanswered requests, listens on the
// channels the server's replies name, sends heartbeats at a quarter of the server's timeout, and
// re-subscribes by itself when the server restarts (a new server_instance in a hello, reply or
// batch) or a granted stream falls silent (the server forgot us, or went away). Everything from
// the network is decoded with thx_msgs::try_decode; what does not decode goes to onError().
// Most programs use it through ClientApp (thx_client/app.hpp), which adds signals, the server's
// hello and a paced loop.
//
// It also sends server commands (sendCommand: reset faults, load a scene) and keeps their replies,
// and follows the server's scene in its hellos: serverScene(), and sceneChanges() /
// onSceneChange() when it changes (another client loaded a scene, or the server restarted on
// another one).
//
// It follows one of the server's devices (ClientOptions::device, index 0 by default; protocol 6):
// on a server with several, each channel carries every device's messages, and only the followed
// device's reach the callbacks, latest*() and StreamStatus::messages; the others are counted
// (StreamStatus::other_device, counters().other_device). latestDeviceState(i) keeps every
// device's newest state for a client of several pens (thx_client/devices.hpp). A client that
// plays every pen (live audio) sets ClientOptions::every_device: then every device's messages are
// delivered (each tagged with its `device`) and none is counted as another device's.
//
// Threads: poll()/service()/subscribe()/unsubscribe()/status()/sendCommand()/serverScene() belong
// to one thread (callbacks run in it, inside poll()). latest*() may be called from any thread.
#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <thx_msgs/contact_batch_t.hpp>
#include <thx_msgs/contact_t.hpp>
#include <thx_msgs/device_state_t.hpp>
#include <thx_msgs/hello_t.hpp>
#include <thx_msgs/protocol.hpp>
#include <thx_msgs/server_command_reply_t.hpp>
#include <thx_msgs/servo_stats_t.hpp>

#include "rt/clock.hpp"
#include "thx_client/control_link.hpp"
#include "thx_client/data_link.hpp"
#include "thx_client/decode_error.hpp"
#include "thx_client/devices.hpp"
#include "thx_client/latest_value.hpp"
#include "thx_client/scene_check.hpp"

namespace lcm {
class LCM;
class ReceiveBuffer;
class Subscription;
}  // namespace lcm

namespace thx::client {

// CLOCK_MONOTONIC in ns: the clock hapticd stamps its ticks with (same host).
inline std::int64_t monotonicNs() { return rt::monotonicNowNs(); }
using Clock = std::function<std::int64_t()>;

enum class SubscriptionState { Pending, Active, Refused };
const char* toString(SubscriptionState s);

struct StreamStatus {
  thx_msgs::Stream stream = thx_msgs::Stream::DeviceState;  // thx_msgs::stream_name(stream) to print it
  bool batch = false;
  double requested_hz = 0.0;
  SubscriptionState state = SubscriptionState::Pending;
  double granted_hz = 0.0;   // from the reply
  std::string channel;       // from the reply
  std::string data_url;      // from the reply: the LCM URL the channel is on ("" = the bus)
  std::string reason;        // refusal, or what the server adjusted
  std::uint64_t messages = 0;      // of the followed device (every device's with every_device): delivered
  std::uint64_t other_device = 0;  // of other devices on this channel: counted, not delivered (0 with every_device)
};

struct ClientOptions {
  std::string client_id;                     // 1-32 of [A-Za-z0-9_-], unique among running clients
  Clock clock;                               // default: monotonicNs (tests pass a fake clock)
  std::int64_t resend_ns = 200'000'000;      // resend an unanswered request after this, doubling up to 2 s
  std::int64_t silence_ns = 3'000'000'000;   // a granted stream without data this long (at least
                                             // 3 periods): ask for it again
  std::int64_t heartbeat_ns = 0;             // 0: a quarter of the server's heartbeat timeout
  unsigned data_queue_capacity = 64;         // LCM queue per data channel (LCM's default is 30);
                                             // a batch stream's is at least 1 s of its batches
  int device = 0;                            // the device followed: its index in hello_t.device_names,
                                             // 0..kMaxDevices-1 (ClientApp::waitForServer checks it)
  bool every_device = false;                 // true: deliver every device's messages, not only `device`'s
                                             // (latest*() then hold the newest of any device)
};

struct ClientCounters {
  std::uint64_t requests_sent = 0;
  std::uint64_t heartbeats_sent = 0;
  std::uint64_t replies = 0;
  std::uint64_t hellos = 0;
  std::uint64_t undecodable = 0;  // bytes on our channels that try_decode refused
  std::uint64_t reconnects = 0;   // server restarts or silences that made us re-subscribe
  std::uint64_t link_errors = 0;  // a control or data URL the server named that could not be opened
  std::uint64_t commands_sent = 0;
  std::uint64_t command_replies = 0;  // replies to commands we sent and were still waiting for
  std::uint64_t other_device = 0;     // stream messages of devices this client does not follow
};

// The server's scene changed (serverScene() went from `from` to `to`).
struct SceneChange {
  SceneIdentity from;
  SceneIdentity to;
  std::int64_t server_instance = 0;  // of the hello that announced `to`
  bool restart = false;              // true: a new server_instance (hapticd restarted on another scene);
                                     // false: a switch within one instance (ACTION_LOAD_SCENE)
};

class Client {
 public:
  // Throws thx::Error (Config) when options.client_id breaks the protocol's rules or
  // options.device is not an index 0..kMaxDevices-1.
  Client(lcm::LCM& lcm, ClientOptions options);
  Client(lcm::LCM& lcm, std::string client_id);  // default options
  ~Client();  // unsubscribes politely (the server would forget us after its timeout anyway)
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  // Asks for a stream (thx_msgs::Stream: DeviceState, Contact, ServoStats) at rate_hz; batch only
  // for Contact. Asking again for the same stream replaces the request. The request goes out at
  // the next poll()/service(). Throws thx::Error (Config) on batch for another stream or a rate
  // that is not a finite number > 0; std::logic_error on a value outside the enum (a cast).
  void subscribe(thx_msgs::Stream stream, double rate_hz, bool batch = false);
  void unsubscribe(thx_msgs::Stream stream);

  // Waits up to timeout_ms for traffic, handles everything queued (callbacks run here), then
  // does the timed work (service()). Returns the number of LCM messages handled, < 0 on error.
  int poll(int timeout_ms);
  // poll() until duration_ns has passed on the client's clock.
  void spinFor(std::int64_t duration_ns);
  // Heartbeats, resends and silence detection only.
  void service();

  // Callbacks, with the receipt time on the client's clock (ns).
  void onDeviceState(LatestValue<thx_msgs::device_state_t>::Callback f) { state_.onMessage(std::move(f)); }
  void onContact(LatestValue<thx_msgs::contact_t>::Callback f) { contact_.onMessage(std::move(f)); }
  void onContactBatch(LatestValue<thx_msgs::contact_batch_t>::Callback f) { batch_.onMessage(std::move(f)); }
  void onServoStats(LatestValue<thx_msgs::servo_stats_t>::Callback f) { stats_.onMessage(std::move(f)); }
  void onHello(LatestValue<thx_msgs::hello_t>::Callback f) { hello_.onMessage(std::move(f)); }
  // Bytes on one of our channels that do not decode (also counted in counters().undecodable).
  void onError(DecodeErrorHandler f) { on_error_ = std::move(f); }
  // A reply changed a stream's status (granted, refused).
  void onStatus(std::function<void(const StreamStatus&)> f) { on_status_ = std::move(f); }

  // Latest values of the followed device; any thread. latestContact() also covers batches (their
  // newest sample).
  std::optional<thx_msgs::device_state_t> latestDeviceState() const { return state_.latest(); }
  // The newest DEVICE_STATE of device `index`, followed or not (nullopt for an index never seen
  // or outside 0..kMaxDevices-1); any thread.
  std::optional<thx_msgs::device_state_t> latestDeviceState(int index) const { return device_states_.latest(index); }
  std::optional<thx_msgs::contact_t> latestContact() const;
  std::optional<thx_msgs::contact_batch_t> latestContactBatch() const { return batch_.latest(); }
  std::optional<thx_msgs::servo_stats_t> latestServoStats() const { return stats_.latest(); }
  std::optional<thx_msgs::hello_t> latestHello() const { return hello_.latest(); }

  std::vector<StreamStatus> status() const;
  std::optional<StreamStatus> status(thx_msgs::Stream stream) const;
  bool allActive() const;  // every requested stream granted
  std::int64_t serverInstance() const { return server_instance_; }

  // ---- Server commands (THX_COMMAND, answered on THX_COMMAND_REPLY) ----
  // Sends server_command_t{action, argument} now and returns its seq (the reply's request_seq;
  // 1, 2, ... per Client). Never resent: a command need not be idempotent (a second load ramps the
  // force down and up again), so a lost command or reply is the caller's timeout. Throws
  // thx::Error (Config) when the argument cannot go out (requireSendable: too long, or not a scene
  // name for ACTION_LOAD_SCENE). ClientApp::command() sends and waits.
  std::int64_t sendCommand(std::int32_t action, std::string_view argument = {});
  // The reply to command `seq` once it arrived, handed over once (then forgotten). The replies of
  // the 64 newest commands are kept; older ones are dropped.
  std::optional<thx_msgs::server_command_reply_t> takeCommandReply(std::int64_t seq);
  // Runs for each reply to a command of ours (in poll()), before takeCommandReply sees it.
  void onCommandReply(std::function<void(const thx_msgs::server_command_reply_t&)> f) { on_command_reply_ = std::move(f); }

  // ---- The server's scene (from its hellos) ----
  // The scene the newest hello names (nullopt before the first hello).
  const std::optional<SceneIdentity>& serverScene() const { return server_scene_; }
  // How many times the server's scene changed since this Client started: +1 for each hello whose
  // scene differs from the previous hello's, within one server instance (a switch) or across a
  // restart. Not for the first hello, not for a restart on the same scene; a hello older than the
  // newest (by seq, within an instance) is not looked at. Poll it at a step boundary: a value that
  // moved means "rebuild on serverScene()" (several switches between two polls count each).
  std::uint64_t sceneChanges() const { return scene_changes_; }
  // Runs in poll() on each such change, after the hello's own callback.
  void onSceneChange(std::function<void(const SceneChange&)> f) { on_scene_change_ = std::move(f); }
  const ClientCounters& counters() const { return counters_; }
  const std::string& clientId() const { return options_.client_id; }
  int device() const { return options_.device; }  // the device followed
  // Sends a message meant for the server alone (THX_COMMAND, THX_CLIENT_FORCE) where it sends its
  // requests and heartbeats: the hello's control URL, which no other client listens on, else the
  // bus. LCM's result (0 = sent).
  template <class M>
  int sendToServer(const std::string& channel, const M& m) {
    return control_.publish(channel, m);
  }
  // The URL requests and heartbeats go to now ("" = the bus), and this client's data URL.
  const std::string& controlUrl() const { return control_.url(); }
  const std::string& dataUrl() const { return data_.url(); }
  // Why the last control or data URL could not be opened ("" if none failed).
  const std::string& lastLinkError() const { return last_link_error_; }

  // Public for LCM's callbacks; not part of the interface.
  void onHelloBytes(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void onReplyBytes(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void onDataBytes(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void onCommandReplyBytes(const lcm::ReceiveBuffer* rbuf, const std::string& channel);

 private:
  struct Entry {
    StreamStatus status;
    std::int64_t params_seq = 0;   // first request seq with the current parameters
    std::int64_t next_send_ns = 0;
    int attempts = 0;
    std::int64_t last_data_ns = 0;  // last message on the data channel (or the grant)
    lcm::Subscription* data_sub = nullptr;
    lcm::LCM* data_lcm = nullptr;  // the LCM data_sub belongs to: lcm_ or data_'s
  };

  void sendRequest(Entry& e, std::int32_t action);
  void sendHeartbeat();
  void serverChanged(std::int64_t instance);  // a restart: every stream is asked for again
  void requestAgain(Entry& e);
  void listen(Entry& e, const std::string& channel, const std::string& data_url);
  lcm::LCM* dataLcmFor(Entry& e, const std::string& data_url);
  void stopListening(Entry& e);
  void undecodable(const std::string& channel, const char* type, std::size_t bytes);
  void linkProblem(std::string problem);
  void trackScene(const thx_msgs::hello_t& h);

  lcm::LCM& lcm_;
  ControlLink control_{lcm_};  // requests and heartbeats (issue 17)
  DataLink data_;              // this client's own data port, when the server names one
  ClientOptions options_;
  Clock clock_;
  std::map<thx_msgs::Stream, Entry> entries_;
  lcm::Subscription* hello_sub_ = nullptr;
  lcm::Subscription* reply_sub_ = nullptr;
  lcm::Subscription* command_reply_sub_ = nullptr;
  std::int64_t server_instance_ = 0;
  std::int64_t seq_ = 0, heartbeat_seq_ = 0;
  std::int64_t next_heartbeat_ns_ = 0;
  std::int64_t heartbeat_period_ns_ = 500'000'000;
  ClientCounters counters_;
  std::string last_link_error_;
  // Commands by seq: nullopt while waiting, then the reply until taken.
  std::map<std::int64_t, std::optional<thx_msgs::server_command_reply_t>> commands_;
  std::int64_t command_seq_ = 0;
  std::function<void(const thx_msgs::server_command_reply_t&)> on_command_reply_;
  std::optional<SceneIdentity> server_scene_;
  std::int64_t scene_instance_ = 0, scene_hello_seq_ = 0;  // the hello server_scene_ came from
  std::uint64_t scene_changes_ = 0;
  std::function<void(const SceneChange&)> on_scene_change_;

  LatestValue<thx_msgs::device_state_t> state_;
  DeviceStateTable device_states_;  // every device's, followed or not
  LatestValue<thx_msgs::contact_t> contact_;
  LatestValue<thx_msgs::contact_batch_t> batch_;
  LatestValue<thx_msgs::servo_stats_t> stats_;
  LatestValue<thx_msgs::hello_t> hello_;
  std::function<void(const StreamStatus&)> on_status_;
  DecodeErrorHandler on_error_;
  std::atomic<bool> newest_contact_from_batch_{false};  // which of contact_/batch_ holds the newest sample
};

}  // namespace thx::client
