#pragma once
// Forces clients ask the server to add to the pen (client_force_t on THX_CLIENT_FORCE): the latest
// message per (client_id, source), ordered by seq, expired after its timeout, summed. Not
// real-time: the receiver thread owns it and hands the sum to the servo through a latest-value
// slot. Bounded: at most kMaxEntries senders; every refusal is counted with its reason.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>

namespace thx_msgs {
struct client_force_t;
}

namespace thx::srv {

struct ClientForceCounters {
  std::uint64_t accepted = 0;
  std::uint64_t stale_seq = 0;     // seq not newer than the last one from that sender
  std::uint64_t bad_values = 0;    // non-finite or above the force limit
  std::uint64_t bad_ids = 0;       // client id or source tag not allowed by the protocol
  std::uint64_t table_full = 0;    // more senders than kMaxEntries
  std::uint64_t other_device = 0;  // client_force_t.device names a device this table is not for
  std::uint64_t expired = 0;

  ClientForceCounters& operator+=(const ClientForceCounters& o) {
    accepted += o.accepted;
    stale_seq += o.stale_seq;
    bad_values += o.bad_values;
    bad_ids += o.bad_ids;
    table_full += o.table_full;
    other_device += o.other_device;
    expired += o.expired;
    return *this;
  }
};

class ClientForceTable {
 public:
  static constexpr int kMaxEntries = 16;

  // Forces above max_force_n (the device's peak force) are refused, not clamped: a client asking
  // for more than the device can give is broken. default_timeout_ns applies when timeout_us <= 0.
  // `device`: the index (hello_t.device_names) of the device whose forces this table sums.
  ClientForceTable(double max_force_n, std::int64_t default_timeout_ns, int device = 0);

  // Returns true if the message was accepted. `now_ns`: the receiver's monotonic clock.
  bool accept(const thx_msgs::client_force_t& message, std::int64_t now_ns);
  // Drops expired entries; returns the sum of the live ones (zero when none).
  Eigen::Vector3d sum(std::int64_t now_ns);
  int liveEntries() const;
  const ClientForceCounters& counters() const { return counters_; }
  double maxForceN() const { return max_force_n_; }
  int device() const { return device_; }

 private:
  struct Entry {
    bool used = false;
    std::string client_id, source;
    std::int64_t seq = 0;
    std::int64_t expires_ns = 0;
    Eigen::Vector3d force_n = Eigen::Vector3d::Zero();
  };
  double max_force_n_;
  std::int64_t default_timeout_ns_;
  int device_;
  std::array<Entry, kMaxEntries> entries_;
  ClientForceCounters counters_;
};

}  // namespace thx::srv
