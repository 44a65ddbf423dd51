#pragma once
// Subscription requests, heartbeats and commands on their way from LCM to the publisher thread.
//
// LCM dispatches callbacks in whichever thread calls handle(): in hapticd that is the receiver
// thread (the only one that may). The callbacks here decode untrusted bytes with
// thx_msgs::try_decode, stamp the receive time and queue the message; the publisher thread takes
// the queue (one short mutex, never held by the servo) and applies it to its SubscriptionTable,
// which therefore has a single owner and needs no locking of its own. Bytes that do not decode
// to one whole message are dropped, counted and logged (rate-limited) with what is wrong.
#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include <thx_msgs/heartbeat_t.hpp>
#include <thx_msgs/server_command_t.hpp>
#include <thx_msgs/subscribe_request_t.hpp>

#include "server/untrusted_input.hpp"

namespace lcm {
class LCM;
class ReceiveBuffer;
class Subscription;
}  // namespace lcm

namespace thx::srv {

struct ControlMessages {
  struct Request {
    thx_msgs::subscribe_request_t msg;
    std::int64_t received_ns = 0;
  };
  struct Heartbeat {
    thx_msgs::heartbeat_t msg;
    std::int64_t received_ns = 0;
  };
  struct Command {
    thx_msgs::server_command_t msg;
    std::int64_t received_ns = 0;
  };
  std::vector<Request> requests;
  std::vector<Heartbeat> heartbeats;
  std::vector<Command> commands;
};

class SubscriptionInbox {
 public:
  // Bounds the queue if the publisher stalls or a client floods: beyond it, messages are dropped
  // and counted (a client resends unanswered requests).
  static constexpr std::size_t kMaxQueued = 4096;

  SubscriptionInbox() = default;
  ~SubscriptionInbox();
  SubscriptionInbox(const SubscriptionInbox&) = delete;
  SubscriptionInbox& operator=(const SubscriptionInbox&) = delete;

  // Subscribes to THX_SUBSCRIBE, THX_HEARTBEAT and THX_COMMAND on `lcm`; detach() (or the
  // destructor) undoes it. Called again with another LCM, it listens on both: hapticd's control
  // URL (what clients send to once they have a hello) and the bus (a first request before any
  // hello, and senders that only know the bus).
  void attach(lcm::LCM& lcm);
  void detach();

  // Moves everything queued into `out` (whose old contents are cleared). Publisher thread.
  void take(ControlMessages& out);

  std::uint64_t undecodable() const { return undecodable_.load(); }
  std::uint64_t overflowed() const { return overflowed_.load(); }

  // Public for LCM's callbacks (and for tests that feed bytes directly).
  void onRequest(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void onHeartbeat(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void onCommand(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void push(const thx_msgs::subscribe_request_t& m, std::int64_t received_ns);
  void push(const thx_msgs::heartbeat_t& m, std::int64_t received_ns);
  void push(const thx_msgs::server_command_t& m, std::int64_t received_ns);

 private:
  template <class T>
  void receive(const lcm::ReceiveBuffer* rbuf, const char* channel);
  template <class Queue, class T>
  void enqueue(Queue& queue, const T& m, std::int64_t received_ns);

  struct Attached {
    lcm::LCM* lcm = nullptr;
    lcm::Subscription* subs[3] = {nullptr, nullptr, nullptr};  // request, heartbeat, command
  };
  std::vector<Attached> attached_;
  std::mutex mutex_;
  ControlMessages queued_;
  std::atomic<std::uint64_t> undecodable_{0}, overflowed_{0};
  InputProblemLog problems_;  // stderr lines naming what was wrong with undecodable bytes
};

}  // namespace thx::srv
