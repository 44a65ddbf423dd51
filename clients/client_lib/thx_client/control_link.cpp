#include "thx_client/control_link.hpp"

namespace thx::client {

std::string ControlLink::use(const std::string& url) {
  if (url == url_) return {};
  control_.reset();
  url_ = url;  // also when it fails: not tried again on every hello
  if (url.empty()) return {};
  auto l = std::make_unique<lcm::LCM>(url);
  if (!l->good()) return "cannot open the server's control URL '" + url + "'; sending to it on the bus instead";
  control_ = std::move(l);
  return {};
}

}  // namespace thx::client
