#pragma once
// The 24-byte cookie each side writes first on a new TCP link (docs/vrpn.md §2).
//
// Layout: "vrpn: ver. 07.38" (16 bytes), two spaces, one log-mode digit '0'..'3' at offset 18,
// NULs at 19..23. We always send log mode '0' (we never ask the peer to log).
//
// Check rules, exactly a stock peer's (docs/vrpn.md §2):
//  - the peer's bytes must equal ours up to and including the last '.' ("vrpn: ver. 07."),
//    otherwise the link is dropped (kBadCookie);
//  - the log-mode byte must be '0'..'3', otherwise the link is dropped (kBadLogMode);
//  - a different minor number is accepted with a warning (PeerCookie::minor_differs);
//  - the other bytes (spaces, NUL tail) are not checked.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "device/vrpn/error.hpp"

namespace thx::vrpn {

inline constexpr std::size_t kCookieSize = 24;
inline constexpr std::string_view kVersionString = "vrpn: ver. 07.38";
// The part of kVersionString a peer must match exactly.
inline constexpr std::string_view kVersionMustMatch = "vrpn: ver. 07.";
inline constexpr std::size_t kLogModeOffset = 18;

using Cookie = std::array<std::uint8_t, kCookieSize>;

// log_mode is clamped to 0..3 (bit 0: peer logs incoming, bit 1: outgoing).
Cookie makeCookie(int log_mode = 0);

struct PeerCookie {
  std::string version;         // the peer's 16-byte version text, non-printables as '?'
  int log_mode = 0;            // what the peer asks us to log; we never log
  bool minor_differs = false;  // not "07.38": interoperable, worth a warning
};

// `bytes` must be exactly kCookieSize long (anything else is kBadCookie).
Result<PeerCookie> checkCookie(std::span<const std::uint8_t> bytes);

}  // namespace thx::vrpn
