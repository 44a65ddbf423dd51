#include "server/data_ports.hpp"

#include <string>

#include "base/error.hpp"

namespace thx::srv {

DataPorts::DataPorts(UdpmUrl bus, int first, int last) : bus_(std::move(bus)), first_(first), last_(last) {
  if (first < 1 || last > 65535 || last < first) {
    throw thx::Error(thx::Error::Kind::Config, "data ports " + std::to_string(first) + "-" + std::to_string(last) +
                                                   ": expected FIRST-LAST with 1 <= FIRST <= LAST <= 65535");
  }
  for (int p = first; p <= last; ++p) free_.push_back(p);
}

std::optional<int> DataPorts::acquire(const std::string& client_id) {
  if (auto it = held_.find(client_id); it != held_.end()) return it->second;
  if (free_.empty()) return std::nullopt;
  const int port = free_.front();
  free_.pop_front();
  held_[client_id] = port;
  return port;
}

void DataPorts::release(const std::string& client_id) {
  auto it = held_.find(client_id);
  if (it == held_.end()) return;
  free_.push_back(it->second);  // back of the queue: reused last
  held_.erase(it);
}

std::optional<int> DataPorts::portOf(const std::string& client_id) const {
  auto it = held_.find(client_id);
  if (it == held_.end()) return std::nullopt;
  return it->second;
}

std::string DataPorts::exhaustedReason() const {
  return "no data port free: all " + std::to_string(size()) + " ports " + std::to_string(first_) + "-" +
         std::to_string(last_) + " are held by clients (hapticd --data-ports)";
}

}  // namespace thx::srv
