#include "server/udpm_url.hpp"

#include <cctype>

namespace thx::srv {

namespace {
constexpr char kScheme[] = "udpm://";
constexpr char kDefaultGroup[] = "239.255.76.67";  // LCM 1.3.1's defaults for "udpm://"
constexpr int kDefaultPort = 7667;
}  // namespace

std::string UdpmUrl::withPort(int p) const {
  std::string url = std::string(kScheme) + group + ":" + std::to_string(p);
  if (!query.empty()) url += "?" + query;
  return url;
}

std::optional<UdpmUrl> parseUdpmUrl(const std::string& url) {
  const std::string scheme = kScheme;
  if (url.compare(0, scheme.size(), scheme) != 0) return std::nullopt;
  const std::size_t q = url.find('?', scheme.size());
  const std::string address = url.substr(scheme.size(), q == std::string::npos ? std::string::npos : q - scheme.size());
  UdpmUrl u;
  if (q != std::string::npos) u.query = url.substr(q + 1);
  const std::size_t colon = address.find(':');
  u.group = address.substr(0, colon);
  if (u.group.empty()) u.group = kDefaultGroup;
  u.port = kDefaultPort;
  if (colon != std::string::npos) {
    const std::string p = address.substr(colon + 1);
    if (p.empty() || p.size() > 5) return std::nullopt;
    for (char c : p) {
      if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
    }
    u.port = std::stoi(p);
    if (u.port < 1 || u.port > 65535) return std::nullopt;
  }
  return u;
}

}  // namespace thx::srv
