#include "device/vrpn/addressing.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>

namespace thx::vrpn {

namespace {

Error badAddress(std::string_view text, std::string_view why) {
  return Error{ErrorCode::kBadAddress, "device address '" + std::string(text) + "': " + std::string(why)};
}

// Decimal digits only (no sign, no spaces), value in [lo, 65535].
bool parsePort(std::string_view s, std::uint16_t lo, std::uint16_t& out) {
  if (s.empty() || s.size() > 5 || !std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return false;
  unsigned v = 0;
  std::from_chars(s.data(), s.data() + s.size(), v);
  if (v < lo || v > 65535) return false;
  out = std::uint16_t(v);
  return true;
}

bool startsWith(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

}  // namespace

Result<DeviceAddress> parseDeviceAddress(std::string_view text) {
  const std::size_t first_at = text.find('@');
  if (first_at == std::string_view::npos) return badAddress(text, "expected Name@location");
  DeviceAddress a;
  a.device = std::string(text.substr(0, first_at));
  if (a.device.empty()) return badAddress(text, "empty device name");
  std::string_view loc = text.substr(text.rfind('@') + 1);

  if (startsWith(loc, "tcp://")) {
    a.mode = ConnectMode::kTcp;
    loc.remove_prefix(6);
  } else if (startsWith(loc, "tcp:")) {
    a.mode = ConnectMode::kTcp;
    loc.remove_prefix(4);
  } else if (startsWith(loc, "x-vrpn://")) {
    loc.remove_prefix(9);
  } else if (startsWith(loc, "file:") || startsWith(loc, "x-vrsh:")) {
    return badAddress(text, "file: and x-vrsh: locations are not supported");
  }
  const std::size_t colon = loc.rfind(':');
  if (colon != std::string_view::npos) {
    if (!parsePort(loc.substr(colon + 1), 1, a.port)) return badAddress(text, "port must be 1..65535");
    loc = loc.substr(0, colon);
  }
  if (loc.empty()) return badAddress(text, "empty host");
  a.host = std::string(loc);
  return a;
}

std::vector<std::uint8_t> encodeLobRequest(std::string_view ip, std::uint16_t port) {
  const std::string text = std::string(ip) + " " + std::to_string(port);
  std::vector<std::uint8_t> out(text.begin(), text.end());
  out.push_back(0);
  return out;
}

Result<LobRequest> parseLobRequest(std::span<const std::uint8_t> datagram) {
  if (datagram.size() > kMaxLobRequest)
    return Error{ErrorCode::kBadLobRequest, "request of " + std::to_string(datagram.size()) + " bytes"};
  const auto end = std::find(datagram.begin(), datagram.end(), std::uint8_t{0});
  const std::string text(datagram.begin(), end);
  if (text.size() >= kMaxLobRequest)  // room for the NUL, so a request we accept we could also send
    return Error{ErrorCode::kBadLobRequest, "request text of " + std::to_string(text.size()) + " bytes"};
  const std::size_t space = text.find(' ');
  if (space == std::string::npos) return Error{ErrorCode::kBadLobRequest, "request without '<host> <port>'"};
  LobRequest r;
  r.host = text.substr(0, space);
  if (r.host.empty() || !std::all_of(r.host.begin(), r.host.end(),
                                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '.'; }))
    return Error{ErrorCode::kBadLobRequest, "request host is not alphanumerics and dots"};
  if (!parsePort(std::string_view(text).substr(space + 1), 1024, r.port))
    return Error{ErrorCode::kBadLobRequest, "request port is not a number in 1024..65535"};
  return r;
}

}  // namespace thx::vrpn
