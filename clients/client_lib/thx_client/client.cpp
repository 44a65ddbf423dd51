#include "thx_client/client.hpp"

#include <poll.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>
#include <type_traits>
#include <thx_msgs/lcm_subscribe.hpp>
#include <thx_msgs/protocol.hpp>

#include "base/error.hpp"
#include "thx_client/commands.hpp"

namespace thx::client {

namespace {
using Req = thx_msgs::subscribe_request_t;
constexpr std::int64_t kMaxResendNs = 2'000'000'000;
constexpr std::size_t kKeptCommands = 64;
}  // namespace

const char* toString(SubscriptionState s) {
  switch (s) {
    case SubscriptionState::Pending: return "pending";
    case SubscriptionState::Active: return "active";
    case SubscriptionState::Refused: return "refused";
  }
  return "?";
}

Client::Client(lcm::LCM& lcm, ClientOptions options)
    : lcm_(lcm), options_(std::move(options)), clock_(options_.clock ? options_.clock : Clock(monotonicNs)) {
  if (!thx_msgs::is_valid_client_id(options_.client_id)) {
    throw thx::Error(thx::Error::Kind::Config,
                     "client_id '" + options_.client_id + "': expected 1 to 32 characters of [A-Za-z0-9_-]");
  }
  if (options_.device < 0 || options_.device >= kMaxDevices) {
    throw thx::Error(thx::Error::Kind::Config, "device " + std::to_string(options_.device) +
                                                   ": expected a device index 0 to " + std::to_string(kMaxDevices - 1));
  }
  if (options_.heartbeat_ns > 0) heartbeat_period_ns_ = options_.heartbeat_ns;
  // Untyped subscriptions + try_decode everywhere: a corrupt datagram must not take us down.
  // Every client sees every reply on the bus: keep room for a burst of them.
  hello_sub_ = thx_msgs::subscribeUntyped(lcm_, thx_msgs::kChannelHello, &Client::onHelloBytes, this);
  reply_sub_ = thx_msgs::subscribeUntyped(lcm_, thx_msgs::kChannelSubscribeReply, &Client::onReplyBytes, this, 256);
  command_reply_sub_ =
      thx_msgs::subscribeUntyped(lcm_, thx_msgs::kChannelCommandReply, &Client::onCommandReplyBytes, this, 256);
  if (!hello_sub_ || !reply_sub_ || !command_reply_sub_)
    linkProblem("LCM could not listen on the bus for the server's hello and replies (its receive socket did not "
                "bind: is the port held by another program?)");
}

Client::Client(lcm::LCM& lcm, std::string client_id) : Client(lcm, [&] {
  ClientOptions o;
  o.client_id = std::move(client_id);
  return o;
}()) {}

Client::~Client() {
  for (auto& [stream, e] : entries_) {
    if (e.status.state == SubscriptionState::Active) sendRequest(e, Req::ACTION_UNSUBSCRIBE);
    stopListening(e);
  }
  if (hello_sub_) lcm_.unsubscribe(hello_sub_);
  if (reply_sub_) lcm_.unsubscribe(reply_sub_);
  if (command_reply_sub_) lcm_.unsubscribe(command_reply_sub_);
}

void Client::subscribe(thx_msgs::Stream stream, double rate_hz, bool batch) {
  const std::string name = thx_msgs::stream_name(stream);
  if (name.empty())
    throw std::logic_error("Client::subscribe: " + std::to_string(int(stream)) + " is not a thx_msgs::Stream");
  if (batch && !thx_msgs::stream_supports_batch(stream))
    throw thx::Error(thx::Error::Kind::Config, "stream " + name + ": only CONTACT can be batched");
  if (!std::isfinite(rate_hz) || rate_hz <= 0.0) {
    throw thx::Error(thx::Error::Kind::Config,
                     "stream " + name + ": rate " + std::to_string(rate_hz) + " Hz: expected a finite number > 0");
  }
  Entry& e = entries_[stream];
  e.status.stream = stream;
  e.status.requested_hz = rate_hz;
  e.status.batch = batch;
  requestAgain(e);
  e.params_seq = seq_ + 1;  // replies to older requests describe older parameters
  if (next_heartbeat_ns_ == 0) next_heartbeat_ns_ = clock_();
}

void Client::unsubscribe(thx_msgs::Stream stream) {
  auto it = entries_.find(stream);
  if (it == entries_.end()) return;
  sendRequest(it->second, Req::ACTION_UNSUBSCRIBE);
  stopListening(it->second);
  entries_.erase(it);
}

void Client::requestAgain(Entry& e) {
  e.status.state = SubscriptionState::Pending;
  e.attempts = 0;
  e.next_send_ns = clock_();  // at the next service()
}

int Client::poll(int timeout_ms) {
  int handled = 0;
  if (data_.lcm()) {  // two LCMs (issue 17): wait on both, then handle what either has
    pollfd fds[2] = {{lcm_.getFileno(), POLLIN, 0}, {data_.lcm()->getFileno(), POLLIN, 0}};
    if (::poll(fds, 2, std::max(0, timeout_ms)) < 0) return -1;  // EINTR: a stop signal
    int r = lcm_.handleTimeout(0);
    while (r > 0) ++handled, r = lcm_.handleTimeout(0);
    const int d = r < 0 ? 0 : data_.drain();
    service();
    if (r < 0 || d < 0) return r < 0 ? r : d;
    return handled + d;
  }
  int r = lcm_.handleTimeout(std::max(0, timeout_ms));
  while (r > 0) {
    ++handled;
    r = lcm_.handleTimeout(0);
  }
  service();
  return r < 0 ? r : handled;
}

void Client::spinFor(std::int64_t duration_ns) {
  const std::int64_t end = clock_() + duration_ns;
  for (std::int64_t now = clock_(); now < end; now = clock_()) {
    poll(int(std::clamp<std::int64_t>((end - now) / 1'000'000, 0, 10)));
  }
}

void Client::service() {
  const std::int64_t now = clock_();
  if (entries_.empty()) return;
  // A granted stream fell silent: the server forgot us (our heartbeats were lost, or we were
  // paused past its timeout) or went away. Hellos may still arrive, so the test is per stream:
  // no data for max(silence_ns, 3 periods) means ask again (a live server keeps an identical
  // subscription as it is, so asking is harmless).
  for (auto& [stream, e] : entries_) {
    if (e.status.state != SubscriptionState::Active || e.status.granted_hz <= 0.0) continue;
    const auto limit = std::max<std::int64_t>(options_.silence_ns, std::int64_t(3e9 / e.status.granted_hz));
    if (now - e.last_data_ns <= limit) continue;
    ++counters_.reconnects;
    requestAgain(e);
  }
  for (auto& [stream, e] : entries_) {
    if (e.status.state != SubscriptionState::Pending || now < e.next_send_ns) continue;
    sendRequest(e, Req::ACTION_SUBSCRIBE);
    const std::int64_t backoff = std::min<std::int64_t>(kMaxResendNs, options_.resend_ns << std::min(e.attempts, 4));
    e.next_send_ns = now + backoff;
    ++e.attempts;
  }
  if (now >= next_heartbeat_ns_) {
    sendHeartbeat();
    next_heartbeat_ns_ = now + heartbeat_period_ns_;
  }
}

void Client::sendRequest(Entry& e, std::int32_t action) {
  Req r{};
  r.utime = clock_() / 1000;
  r.seq = ++seq_;
  r.client_id = options_.client_id;
  r.stream = thx_msgs::stream_name(e.status.stream);
  r.action = action;
  r.rate_hz = e.status.requested_hz;
  r.batch = e.status.batch;
  control_.publish(thx_msgs::kChannelSubscribe, r);
  ++counters_.requests_sent;
}

void Client::sendHeartbeat() {
  thx_msgs::heartbeat_t h{};
  h.utime = clock_() / 1000;
  h.seq = ++heartbeat_seq_;
  h.server_instance = server_instance_;
  h.client_id = options_.client_id;
  control_.publish(thx_msgs::kChannelHeartbeat, h);
  ++counters_.heartbeats_sent;
}

void Client::serverChanged(std::int64_t instance) {
  const bool restart = server_instance_ != 0 && instance != server_instance_;
  server_instance_ = instance;
  if (!restart) return;
  ++counters_.reconnects;
  for (auto& [stream, e] : entries_) requestAgain(e);
}

void Client::onHelloBytes(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  thx_msgs::hello_t h;
  if (thx_msgs::try_decode(rbuf->data, rbuf->data_size, h) < 0)
    return undecodable(thx_msgs::kChannelHello, thx_msgs::hello_t::getTypeName(), rbuf->data_size);
  ++counters_.hellos;
  if (std::string problem = control_.use(h.control_url); !problem.empty()) linkProblem(std::move(problem));
  const bool first = server_instance_ == 0;
  serverChanged(h.server_instance);
  if (first) {
    for (auto& [stream, e] : entries_) {
      if (e.status.state == SubscriptionState::Pending) e.next_send_ns = clock_();  // the server is up: ask now
    }
  }
  hello_.deliver(h, clock_());
  trackScene(h);
}

void Client::trackScene(const thx_msgs::hello_t& h) {
  const bool same_instance = server_scene_ && h.server_instance == scene_instance_;
  // LCM keeps one sender's order on one channel, but a hello queued before a switch and handled
  // after the switch's hello must not switch back.
  if (same_instance && h.seq <= scene_hello_seq_) return;
  const std::optional<SceneIdentity> before = server_scene_;
  server_scene_ = sceneOf(h);
  scene_instance_ = h.server_instance;
  scene_hello_seq_ = h.seq;
  if (!before || *before == *server_scene_) return;
  ++scene_changes_;
  if (on_scene_change_) {
    SceneChange c;
    c.from = *before;
    c.to = *server_scene_;
    c.server_instance = h.server_instance;
    c.restart = !same_instance;
    on_scene_change_(c);
  }
}

std::int64_t Client::sendCommand(std::int32_t action, std::string_view argument) {
  requireSendable(action, argument);
  thx_msgs::server_command_t c{};
  c.utime = clock_() / 1000;
  c.seq = ++command_seq_;
  c.client_id = options_.client_id;
  c.action = action;
  c.argument = std::string(argument);
  commands_.emplace(c.seq, std::nullopt);
  while (commands_.size() > kKeptCommands) commands_.erase(commands_.begin());  // the oldest
  control_.publish(thx_msgs::kChannelCommand, c);  // to the control URL, like requests (issue 17)
  ++counters_.commands_sent;
  return c.seq;
}

std::optional<thx_msgs::server_command_reply_t> Client::takeCommandReply(std::int64_t seq) {
  auto it = commands_.find(seq);
  if (it == commands_.end() || !it->second) return std::nullopt;
  std::optional<thx_msgs::server_command_reply_t> reply = std::move(it->second);
  commands_.erase(it);
  return reply;
}

void Client::onCommandReplyBytes(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  thx_msgs::server_command_reply_t r;
  if (thx_msgs::try_decode(rbuf->data, rbuf->data_size, r) < 0)
    return undecodable(thx_msgs::kChannelCommandReply, thx_msgs::server_command_reply_t::getTypeName(),
                       rbuf->data_size);
  if (r.client_id != options_.client_id) return;  // another client's answer
  // Only commands we sent and still wait for: not a second reply, not another process's with our id.
  auto it = commands_.find(r.request_seq);
  if (it == commands_.end() || it->second) return;
  ++counters_.command_replies;
  it->second = r;
  if (on_command_reply_) on_command_reply_(r);
}

void Client::onReplyBytes(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  thx_msgs::subscribe_reply_t r;
  if (thx_msgs::try_decode(rbuf->data, rbuf->data_size, r) < 0)
    return undecodable(thx_msgs::kChannelSubscribeReply, thx_msgs::subscribe_reply_t::getTypeName(), rbuf->data_size);
  if (r.client_id != options_.client_id) return;  // another client's answer
  ++counters_.replies;
  if (r.action != Req::ACTION_SUBSCRIBE) return;
  const std::optional<thx_msgs::Stream> stream = thx_msgs::parse_stream(r.stream);
  if (!stream) return;  // not one we ask for
  auto it = entries_.find(*stream);
  if (it == entries_.end() || r.request_seq < it->second.params_seq) return;  // stale
  if (r.server_instance != server_instance_) serverChanged(r.server_instance);
  Entry& e = it->second;
  if (r.accepted) {
    if (e.status.state != SubscriptionState::Active) e.last_data_ns = clock_();  // the silence clock starts
    e.status.state = SubscriptionState::Active;
    e.status.granted_hz = r.rate_hz;
    e.status.reason = r.reason;
    listen(e, r.channel, r.data_url);
    if (options_.heartbeat_ns <= 0 && r.heartbeat_timeout_us > 0) {
      heartbeat_period_ns_ = std::max<std::int64_t>(10'000'000, r.heartbeat_timeout_us * 1000 / 4);
      next_heartbeat_ns_ = std::min(next_heartbeat_ns_, clock_() + heartbeat_period_ns_);
    }
  } else {
    e.status.state = SubscriptionState::Refused;
    e.status.granted_hz = 0.0;
    e.status.reason = r.reason;
    stopListening(e);
  }
  if (on_status_) on_status_(e.status);
}

void Client::listen(Entry& e, const std::string& channel, const std::string& data_url) {
  lcm::LCM* target = dataLcmFor(e, data_url);
  if (e.data_sub && e.status.channel == channel && e.data_lcm == target) return;
  stopListening(e);
  // Channel names are used as LCM regexes; the server's are plain [A-Za-z0-9_.-].
  e.status.channel = channel;
  e.status.data_url = data_url;
  e.data_lcm = target;
  // A batch stream must lose nothing: after a stall of the server's publisher (or of this
  // process) its batches come in a burst, so it may queue one second of them (issue 17: bursts
  // of ~400 overflowed 64 at 64 clients on two busy cores).
  const double burst = e.status.batch ? e.status.granted_hz : 0.0;
  e.data_sub = thx_msgs::subscribeUntyped(*target, channel, &Client::onDataBytes, this,
                                          int(std::max<double>(options_.data_queue_capacity, burst)));
  if (!e.data_sub) {
    // Nothing will arrive: the silence check asks again later, and LCM tries the bind again then.
    linkProblem("cannot listen for " + channel + " on '" + (data_url.empty() ? std::string("the bus") : data_url) +
                "': LCM's receive socket did not bind (is the port held by another program?)");
    e.data_lcm = nullptr;
  }
}

// The LCM a reply's data_url names: the bus for "", else DataLink's. A new URL (the server
// restarted, or gave us another port) closes the old one; the streams that were on it are asked
// for again, and their replies name the new one.
lcm::LCM* Client::dataLcmFor(Entry& e, const std::string& data_url) {
  if (data_url.empty()) return &lcm_;
  if (data_url == data_.url() && data_.lcm()) return data_.lcm();
  for (auto& [stream, other] : entries_) {
    if (!other.data_lcm || other.data_lcm == &lcm_) continue;
    stopListening(other);
    if (&other != &e && other.status.state == SubscriptionState::Active) requestAgain(other);
  }
  if (std::string problem = data_.open(data_url); !problem.empty()) {
    linkProblem(std::move(problem));
    return &lcm_;  // nothing will arrive: the silence check asks again later
  }
  return data_.lcm();
}

void Client::stopListening(Entry& e) {
  if (e.data_sub && e.data_lcm) e.data_lcm->unsubscribe(e.data_sub);
  e.data_sub = nullptr;
  e.data_lcm = nullptr;
  e.status.channel.clear();
}

void Client::onDataBytes(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
  Entry* e = nullptr;
  for (auto& [stream, candidate] : entries_) {
    if (candidate.data_sub && candidate.status.channel == channel) e = &candidate;
  }
  if (!e) return;
  const std::int64_t now = clock_();
  const thx_msgs::Stream stream = e->status.stream;
  // Decodes into `m` (false and reported when the bytes do not decode as `type`).
  auto decode = [&](auto& m) {
    if (thx_msgs::try_decode(rbuf->data, rbuf->data_size, m) >= 0) return true;
    undecodable(channel, std::decay_t<decltype(m)>::getTypeName(), rbuf->data_size);
    return false;
  };
  // Any device's message shows the subscription alive (the silence check); only the followed
  // device's is delivered (every device's with every_device), the others' are counted (protocol
  // 6: one channel, every device).
  auto followed = [&](const auto& m) {
    e->last_data_ns = now;
    if (options_.every_device || m.device == options_.device) return true;
    ++e->status.other_device;
    ++counters_.other_device;
    return false;
  };
  // Counted before the callback runs: a callback may unsubscribe, which destroys *e.
  auto deliver = [&](auto& value, const auto& m) {
    ++e->status.messages;
    value.deliver(m, now);
  };
  if (stream == thx_msgs::Stream::DeviceState) {
    thx_msgs::device_state_t m;
    if (!decode(m)) return;
    device_states_.store(m);
    if (followed(m)) deliver(state_, m);
  } else if (stream == thx_msgs::Stream::Contact && e->status.batch) {
    thx_msgs::contact_batch_t m;
    if (!decode(m)) return;
    if (m.server_instance != server_instance_) serverChanged(m.server_instance);
    if (!followed(m)) return;
    newest_contact_from_batch_ = true;
    deliver(batch_, m);
  } else if (stream == thx_msgs::Stream::Contact) {
    thx_msgs::contact_t m;
    if (!decode(m) || !followed(m)) return;
    newest_contact_from_batch_ = false;
    deliver(contact_, m);
  } else {
    thx_msgs::servo_stats_t m;
    if (decode(m) && followed(m)) deliver(stats_, m);
  }
}

void Client::linkProblem(std::string problem) {
  ++counters_.link_errors;
  last_link_error_ = std::move(problem);
}

void Client::undecodable(const std::string& channel, const char* type, std::size_t bytes) {
  ++counters_.undecodable;
  if (on_error_) on_error_(DecodeError{channel, type, bytes});
}

std::optional<thx_msgs::contact_t> Client::latestContact() const {
  if (newest_contact_from_batch_) {
    auto b = batch_.latest();
    if (b && !b->samples.empty()) return b->samples.back();
    return std::nullopt;
  }
  return contact_.latest();
}

std::vector<StreamStatus> Client::status() const {
  std::vector<StreamStatus> out;
  for (const auto& [stream, e] : entries_) out.push_back(e.status);
  return out;
}

std::optional<StreamStatus> Client::status(thx_msgs::Stream stream) const {
  auto it = entries_.find(stream);
  if (it == entries_.end()) return std::nullopt;
  return it->second.status;
}

bool Client::allActive() const {
  if (entries_.empty()) return false;
  for (const auto& [stream, e] : entries_) {
    if (e.status.state != SubscriptionState::Active) return false;
  }
  return true;
}

}  // namespace thx::client
