#include "server/client_force_table.hpp"

#include <thx_msgs/client_force_t.hpp>
#include <thx_msgs/protocol.hpp>

namespace thx::srv {

ClientForceTable::ClientForceTable(double max_force_n, std::int64_t default_timeout_ns, int device)
    : max_force_n_(max_force_n), default_timeout_ns_(default_timeout_ns), device_(device) {}

bool ClientForceTable::accept(const thx_msgs::client_force_t& m, std::int64_t now_ns) {
  if (!thx_msgs::is_valid_client_id(m.client_id) || !thx_msgs::is_valid_source_tag(m.source)) {
    ++counters_.bad_ids;
    return false;
  }
  if (m.device != device_) {
    ++counters_.other_device;
    return false;
  }
  const Eigen::Vector3d f(m.f_world[0], m.f_world[1], m.f_world[2]);
  if (!f.allFinite() || f.norm() > max_force_n_) {
    ++counters_.bad_values;
    return false;
  }
  Entry* slot = nullptr;
  Entry* free_slot = nullptr;
  for (Entry& e : entries_) {
    if (e.used && e.client_id == m.client_id && e.source == m.source) slot = &e;
    if (!e.used && !free_slot) free_slot = &e;
  }
  if (slot && m.seq <= slot->seq) {
    ++counters_.stale_seq;
    return false;
  }
  if (!slot) {
    if (!free_slot) {
      ++counters_.table_full;
      return false;
    }
    slot = free_slot;
    slot->used = true;
    slot->client_id = m.client_id;
    slot->source = m.source;
  }
  slot->seq = m.seq;
  slot->force_n = f;
  // Bound the timeout: a client cannot pin a force on the pen for ever.
  const std::int64_t timeout_ns =
      m.timeout_us > 0 ? std::min<std::int64_t>(m.timeout_us, 1'000'000) * 1000 : default_timeout_ns_;
  slot->expires_ns = now_ns + timeout_ns;
  ++counters_.accepted;
  return true;
}

Eigen::Vector3d ClientForceTable::sum(std::int64_t now_ns) {
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (Entry& e : entries_) {
    if (!e.used) continue;
    if (now_ns >= e.expires_ns) {
      e.used = false;
      ++counters_.expired;
      continue;
    }
    total += e.force_n;
  }
  return total;
}

int ClientForceTable::liveEntries() const {
  int n = 0;
  for (const Entry& e : entries_) n += e.used ? 1 : 0;
  return n;
}

}  // namespace thx::srv
