#pragma once
// The receiver thread: what enters hapticd over LCM. It is the only thread that calls
// lcm.handle(), so every LCM callback runs here: client forces (THX_CLIENT_FORCE, below) and the
// publisher's SubscriptionInbox (THX_SUBSCRIBE, THX_HEARTBEAT, THX_COMMAND: decoded and queued for the
// publisher thread, server/subscription_inbox.hpp).
// Messages are taken untyped and decoded with thx_msgs::try_decode (LCM 1.3.1's typed decoders
// can crash on corrupt input, docs/messages.md), checked, kept per sender and per device (one
// ClientForceTable per device, chosen by client_force_t.device), and each device's sum is written
// to its servo's latest-value slot: on every accepted message and every 10 ms while any force is
// live, so a servo's own staleness timeout only fires if this thread stalls.
#include <atomic>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "server/client_force_table.hpp"
#include "rt/latest_slot.hpp"
#include "server/servo.hpp"
#include "server/untrusted_input.hpp"

namespace lcm {
class LCM;
class ReceiveBuffer;
}

namespace thx::srv {

// A device clients may push: its servo's slot (Servo::clientForceSlot()) and its peak force.
struct ForcedDevice {
  rt::LatestSlot<ClientForce>* slot = nullptr;
  double max_force_n = 0.0;
};

class Receiver {
 public:
  static constexpr std::size_t kMaxDevices = 16;  // ServoGroup::kMaxDevices
  // Device i of `devices` takes the client forces whose `device` is i (1..16 devices).
  Receiver(lcm::LCM& lcm, std::vector<ForcedDevice> devices);
  // One device.
  Receiver(lcm::LCM& lcm, rt::LatestSlot<ClientForce>& slot, double max_force_n)
      : Receiver(lcm, std::vector<ForcedDevice>{{&slot, max_force_n}}) {}
  ~Receiver();
  // Also takes client forces from, and handles, `control` (hapticd's control URL, which only it
  // listens on: docs/clients.md §6). Before start().
  void listenAlsoOn(lcm::LCM& control);
  // > 0: the thread asks for SCHED_FIFO at this priority (like the publisher's; heartbeats must
  // not wait behind busy clients past the timeout). Before start().
  void setFifoPriority(int priority) { fifo_priority_ = priority; }
  void start();
  void stop();
  ClientForceCounters counters() const;  // summed over the devices
  std::uint64_t undecodable() const { return undecodable_.load(); }

  // Public for LCM's callback; not part of the interface.
  void onClientForce(const lcm::ReceiveBuffer* rbuf, const std::string& channel);

 private:
  void listen(lcm::LCM& lcm);  // THX_CLIENT_FORCE on `lcm`; warns when LCM cannot
  void run();
  void publishSums(std::int64_t now_ns);
  void publishSum(std::size_t device, std::int64_t now_ns);
  void drain();  // handles whatever is queued on every LCM, without waiting

  lcm::LCM& lcm_;
  std::vector<lcm::LCM*> lcms_;  // lcm_ first, then listenAlsoOn()'s
  int fifo_priority_ = 0;
  std::vector<rt::LatestSlot<ClientForce>*> slots_;  // by device
  std::vector<ClientForceTable> tables_;              // by device
  mutable std::mutex table_mutex_;  // counters() from other threads; never the servo
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> undecodable_{0};
  std::vector<bool> was_live_;  // by device
  InputProblemLog problems_;  // undecodable or refused client forces, on stderr (rate-limited)
};

}  // namespace thx::srv
