#include "scenes/vrpn_address.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>

namespace thx::scene {

namespace {
std::optional<VrpnAddress> reject(std::string* problem, const char* why) {
  if (problem) *problem = why;
  return std::nullopt;
}
bool hasSpace(const std::string& s) {
  return std::any_of(s.begin(), s.end(), [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; });
}
}  // namespace

std::optional<VrpnAddress> parseVrpnAddress(const std::string& text, std::string* problem) {
  VrpnAddress a;
  const std::size_t at = text.find('@');
  if (at == std::string::npos) return reject(problem, "no '@' between device name and host");
  a.device = text.substr(0, at);
  std::string rest = text.substr(at + 1);
  if (a.device.empty()) return reject(problem, "empty device name before '@'");
  if (hasSpace(text)) return reject(problem, "contains white space");
  const std::size_t scheme_end = rest.find("://");
  if (scheme_end != std::string::npos) {
    a.scheme = rest.substr(0, scheme_end);
    if (a.scheme != "tcp") return reject(problem, "unsupported scheme (only tcp:// is served)");
    rest = rest.substr(scheme_end + 3);
  }
  const std::size_t colon = rest.rfind(':');
  a.host = colon == std::string::npos ? rest : rest.substr(0, colon);
  if (a.host.empty()) return reject(problem, "empty host");
  if (a.host.find('@') != std::string::npos || a.host.find('/') != std::string::npos)
    return reject(problem, "malformed host");
  if (colon != std::string::npos) {
    const std::string port = rest.substr(colon + 1);
    int value = 0;
    const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
    if (port.empty() || ec != std::errc() || end != port.data() + port.size() || value < 1 || value > 65535)
      return reject(problem, "port is not an integer in [1, 65535]");
    a.port = value;
  } else {
    a.port = kVrpnDefaultPort;
  }
  return a;
}

}  // namespace thx::scene
