#pragma once
// The udpm ports hapticd hands out, one per client, for that client's streams (issue 17,
// docs/clients.md §6). On one shared udpm port every process receives every datagram and pays a
// kernel wake-up for each (docs/results/issue17/transport.jsonl), so N clients cost N times the
// total traffic; a port of its own makes a client receive only its own streams.
//
// A client gets a port with its first granted subscription and keeps it until it leaves (its last
// unsubscription) or expires (no heartbeat); the port then goes back to the pool. A port is
// handed out again only after every other free port: the one released longest ago is taken first,
// so a client that was forgotten but still listens (paused, not dead) is unlikely to wake for
// someone else's streams. With every port held, a new client is refused with a reason naming the
// range and the option. Pure bookkeeping, owned by the publisher thread's SubscriptionTable.
#include <deque>
#include <map>
#include <optional>
#include <string>

#include "server/udpm_url.hpp"

namespace thx::srv {

class DataPorts {
 public:
  // Ports first..last (inclusive) on `bus`'s group and query. Throws thx::Error (Config) when
  // the range is empty or outside 1..65535 (hapticd checks --data-ports before: server/port_plan.hpp).
  DataPorts(UdpmUrl bus, int first, int last);

  // The port `client_id` holds, else the free port released longest ago (then the lowest never
  // used); nullopt when every port is held.
  std::optional<int> acquire(const std::string& client_id);
  // Gives the client's port back (nothing when it holds none).
  void release(const std::string& client_id);
  std::optional<int> portOf(const std::string& client_id) const;

  // subscribe_reply_t.data_url for a port: the bus URL with that port.
  std::string url(int port) const { return bus_.withPort(port); }
  // Why a new client was refused: "no data port free: all 2 ports 7669-7670 are held by clients
  // (hapticd --data-ports)".
  std::string exhaustedReason() const;

  int first() const { return first_; }
  int last() const { return last_; }
  int size() const { return last_ - first_ + 1; }
  int held() const { return int(held_.size()); }

 private:
  UdpmUrl bus_;
  int first_, last_;
  std::deque<int> free_;              // front: taken next
  std::map<std::string, int> held_;   // client id -> port
};

}  // namespace thx::srv
