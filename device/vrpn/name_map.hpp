#pragma once
// Name <-> id tables for one kind of name (senders, or types) on one connection (docs/vrpn.md §5).
//
// Ids belong to whoever sends: the ids we put in our messages (local) and the ids the peer puts in
// its messages (remote) are separate spaces, joined only by name. So a message's remote type id
// is resolved remote id -> name (from the peer's description) -> our local id.
//
// Contract:
//  - addLocal(name) is idempotent: the same name always gets the same local id; ids are dense,
//    from 0, in registration order; at most kMaxNames. Local names never move (views into them
//    stay valid for the map's lifetime).
//  - defineRemote(id, name) accepts a description at any time, any number of times: an echo is a
//    no-op, a redefinition replaces the old name. Ids outside [0, kMaxNames) are an error.
//  - Storage is bounded by kMaxNames entries per table, each name <= kMaxNameLength bytes.
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "device/vrpn/error.hpp"

namespace thx::vrpn {

inline constexpr std::int32_t kNoId = -1;

class NameMap {
 public:
  // Our id for `name`, registering it if new; kNoId if the name is invalid or the table full.
  std::int32_t addLocal(std::string_view name);
  // Our id for `name`, or kNoId.
  std::int32_t findLocal(std::string_view name) const;
  std::string_view localName(std::int32_t local_id) const;  // empty if unknown
  std::int32_t localCount() const { return std::int32_t(local_names_.size()); }

  // The peer's description of `remote_id`. Returns true if it added or changed a mapping.
  Result<bool> defineRemote(std::int32_t remote_id, std::string_view name);
  bool remoteDescribed(std::int32_t remote_id) const;
  std::string_view remoteName(std::int32_t remote_id) const;  // empty if never described
  // Our id for the peer's id (by name), or kNoId if undescribed or not registered locally.
  std::int32_t toLocal(std::int32_t remote_id) const;

 private:
  std::deque<std::string> local_names_;  // deque: views handed out stay valid as it grows
  std::map<std::string, std::int32_t, std::less<>> local_ids_;
  std::vector<std::string> remote_names_;      // by remote id; "" = undescribed
  std::vector<std::int32_t> remote_to_local_;  // cache of the by-name join, kNoId if none
};

}  // namespace thx::vrpn
