#include "device/vrpn/cookie.hpp"

#include <algorithm>

namespace thx::vrpn {

Cookie makeCookie(int log_mode) {
  Cookie c{};
  std::copy(kVersionString.begin(), kVersionString.end(), c.begin());
  c[kVersionString.size()] = ' ';
  c[kVersionString.size() + 1] = ' ';
  c[kLogModeOffset] = std::uint8_t('0' + std::clamp(log_mode, 0, 3));
  return c;  // offsets 19..23 stay NUL
}

namespace {

std::string printable(std::span<const std::uint8_t> bytes) {
  std::string s;
  for (std::uint8_t b : bytes) s.push_back(b >= 0x20 && b < 0x7f ? char(b) : '?');
  return s;
}

}  // namespace

Result<PeerCookie> checkCookie(std::span<const std::uint8_t> bytes) {
  if (bytes.size() != kCookieSize)
    return Error{ErrorCode::kBadCookie,
                 "cookie is " + std::to_string(bytes.size()) + " bytes, expected " + std::to_string(kCookieSize)};
  PeerCookie peer;
  peer.version = printable(bytes.first(kVersionString.size()));
  if (!std::equal(kVersionMustMatch.begin(), kVersionMustMatch.end(), bytes.begin(),
                  [](char a, std::uint8_t b) { return std::uint8_t(a) == b; }))
    return Error{ErrorCode::kBadCookie,
                 "peer version '" + peer.version + "' is not '" + std::string(kVersionMustMatch) + "xx'"};
  const std::uint8_t mode = bytes[kLogModeOffset];
  if (mode < '0' || mode > '3')
    return Error{ErrorCode::kBadLogMode,
                 "peer cookie log-mode byte is " + std::to_string(mode) + ", not ASCII '0'..'3'"};
  peer.log_mode = mode - '0';
  peer.minor_differs = !std::equal(kVersionString.begin() + kVersionMustMatch.size(), kVersionString.end(),
                                   bytes.begin() + kVersionMustMatch.size(),
                                   [](char a, std::uint8_t b) { return std::uint8_t(a) == b; });
  return peer;
}

}  // namespace thx::vrpn
