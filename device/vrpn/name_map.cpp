#include "device/vrpn/name_map.hpp"

#include "device/vrpn/limits.hpp"
#include "device/vrpn/system_messages.hpp"

namespace thx::vrpn {

std::int32_t NameMap::addLocal(std::string_view name) {
  if (const std::int32_t id = findLocal(name); id != kNoId) return id;
  if (!isValidName(name) || localCount() >= kMaxNames) return kNoId;
  const std::int32_t id = localCount();
  local_names_.emplace_back(name);
  local_ids_.emplace(std::string(name), id);
  // The peer may have described this name before we cared about it.
  for (std::size_t r = 0; r < remote_names_.size(); ++r)
    if (remote_names_[r] == name) remote_to_local_[r] = id;
  return id;
}

std::int32_t NameMap::findLocal(std::string_view name) const {
  const auto it = local_ids_.find(name);
  return it == local_ids_.end() ? kNoId : it->second;
}

std::string_view NameMap::localName(std::int32_t local_id) const {
  if (local_id < 0 || local_id >= localCount()) return {};
  return local_names_[std::size_t(local_id)];
}

Result<bool> NameMap::defineRemote(std::int32_t remote_id, std::string_view name) {
  if (remote_id < 0 || remote_id >= kMaxNames)
    return Error{ErrorCode::kIdOutOfRange,
                 "description of id " + std::to_string(remote_id) + " outside [0, " + std::to_string(kMaxNames) + ")"};
  if (!isValidName(name)) return Error{ErrorCode::kBadDescription, "description with an invalid name"};
  const auto r = std::size_t(remote_id);
  if (r >= remote_names_.size()) {
    remote_names_.resize(r + 1);
    remote_to_local_.resize(r + 1, kNoId);
  }
  if (remote_names_[r] == name) return false;  // an echo or a repeat
  remote_names_[r] = std::string(name);
  remote_to_local_[r] = findLocal(name);
  return true;
}

bool NameMap::remoteDescribed(std::int32_t remote_id) const { return !remoteName(remote_id).empty(); }

std::string_view NameMap::remoteName(std::int32_t remote_id) const {
  if (remote_id < 0 || std::size_t(remote_id) >= remote_names_.size()) return {};
  return remote_names_[std::size_t(remote_id)];
}

std::int32_t NameMap::toLocal(std::int32_t remote_id) const {
  if (remote_id < 0 || std::size_t(remote_id) >= remote_to_local_.size()) return kNoId;
  return remote_to_local_[std::size_t(remote_id)];
}

}  // namespace thx::vrpn
