#include "thx_client/data_link.hpp"

#include <lcm/lcm-cpp.hpp>

namespace thx::client {

DataLink::DataLink() = default;
DataLink::~DataLink() = default;

std::string DataLink::open(const std::string& url) {
  close();
  auto l = std::make_unique<lcm::LCM>(url);
  if (!l->good()) {
    return "cannot open the data URL '" + url +
           "' the server named for this client's streams (no multicast route, or the port is not allowed?)";
  }
  lcm_ = std::move(l);
  url_ = url;
  return {};
}

void DataLink::close() {
  lcm_.reset();
  url_.clear();
}

int DataLink::drain() {
  if (!lcm_) return 0;
  int handled = 0, r = 0;
  while ((r = lcm_->handleTimeout(0)) > 0) ++handled;
  return r < 0 ? r : handled;
}

}  // namespace thx::client
