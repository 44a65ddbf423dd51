#pragma once
// System messages: negative type ids (docs/vrpn.md §5).
//
//  -1 SENDER_DESCRIPTION  header.sender = the id being defined; body: uint32 n = strlen+1, name, NUL
//  -2 TYPE_DESCRIPTION    same layout, header.sender = the type id being defined
//  -3 UDP_DESCRIPTION     header.sender = UDP port; body: ASCII IP + NUL   (we are TCP-only: ignored)
//  -4 LOG_DESCRIPTION     header.sender = log mode; body: two lengths + names (we never log: ignored)
//  -5 DISCONNECT          never on the wire; ignored if seen
//
// Description decoding is strict about sizes, lenient about the NUL (the stock receiver truncates
// the name to the length word): payload <= 100 bytes, payload == 4 + n, name = the n bytes up to
// the first NUL, non-empty. Ids must lie in [0, kMaxNames).
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "device/vrpn/error.hpp"
#include "device/vrpn/header.hpp"

namespace thx::vrpn {

inline constexpr std::int32_t kSenderDescription = -1;
inline constexpr std::int32_t kTypeDescription = -2;
inline constexpr std::int32_t kUdpDescription = -3;
inline constexpr std::int32_t kLogDescription = -4;
inline constexpr std::int32_t kDisconnectMessage = -5;

// Names every stock peer registers first (sender 0, types 0..3). Described on the wire, never
// used in a message. We register them too so our ids look like a stock peer's; never assume ids.
inline constexpr std::string_view kControlSenderName = "VRPN Control";
inline constexpr std::string_view kControlTypeNames[] = {
    "VRPN_Connection_Got_First_Connection",
    "VRPN_Connection_Got_Connection",
    "VRPN_Connection_Dropped_Connection",
    "VRPN_Connection_Dropped_Last_Connection",
};

// True for names we can describe: 1..kMaxNameLength bytes, no NUL.
bool isValidName(std::string_view name);

// Appends the body of a sender or type description (precondition: isValidName(name)).
void encodeDescription(std::string_view name, std::vector<std::uint8_t>& out);

// The described name; the view points into `payload`.
Result<std::string_view> decodeDescription(std::span<const std::uint8_t> payload);

}  // namespace thx::vrpn
