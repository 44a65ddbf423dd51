#pragma once
// Byte transcripts captured from stock VRPN programs, copied from
// the captures of docs/vrpn.md §11 (hex exactly as the team recorded them), plus a hex parser.
#include <cctype>
#include <cstdint>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace thx::vrpn::transcript {

// "00 0a ff" -> {0x00, 0x0a, 0xff}; whitespace between bytes is ignored.
inline std::vector<std::uint8_t> hex(std::string_view text) {
  std::vector<std::uint8_t> out;
  int nibbles = 0;
  std::uint8_t acc = 0;
  for (char c : text) {
    if (std::isspace(static_cast<unsigned char>(c))) continue;
    const int v = std::isdigit(static_cast<unsigned char>(c)) ? c - '0' : std::tolower(c) - 'a' + 10;
    if (v < 0 || v > 15) throw std::invalid_argument("bad hex digit");
    acc = std::uint8_t((acc << 4) | v);
    if (++nibbles % 2 == 0) out.push_back(acc);
  }
  if (nibbles % 2 != 0) throw std::invalid_argument("odd number of hex digits");
  return out;
}

inline std::vector<std::uint8_t> concat(std::initializer_list<std::vector<std::uint8_t>> parts) {
  std::vector<std::uint8_t> out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

// Mode A: the client's UDP connection request ("lob"), 16 bytes.
inline constexpr std::string_view kLobRequest = "31 32 37 2e 30 2e 30 2e 31 20 33 33 33 30 39 00";

// Cookie, identical both ways.
inline constexpr std::string_view kCookie = "76 72 70 6e 3a 20 76 65 72 2e 20 30 37 2e 33 38 20 20 30 00 00 00 00 00";

// S->C UDP_DESCRIPTION: port 52198 in the sender word, "127.0.0.1\0" padded to 16, seq 0.
inline constexpr std::string_view kUdpDescription =
    "00 00 00 22 6b 02 29 12 00 0b 5c 83 00 00 cb e6 ff ff ff fd 00 00 00 00"
    "31 32 37 2e 30 2e 30 2e 31 00 00 00 00 00 00 00";

// S->C SENDER_DESCRIPTION id 0 "VRPN Control", seq 1.
inline constexpr std::string_view kSenderVrpnControl =
    "00 00 00 29 6b 02 29 12 00 0b 5c 86 00 00 00 00 ff ff ff ff 00 00 00 01"
    "00 00 00 0d 56 52 50 4e 20 43 6f 6e 74 72 6f 6c 00 00 00 00 00 00 00 00";

// S->C SENDER_DESCRIPTION id 1 "Tracker0": only the unpadded body was printed.
inline constexpr std::string_view kSenderTracker0Body = "00 00 00 09 54 72 61 63 6b 65 72 30 00";

// S->C TYPE_DESCRIPTION id 4 "vrpn_Tracker Pos_Quat", seq 10.
inline constexpr std::string_view kTypePosQuat =
    "00 00 00 32 6b 02 29 12 00 0b 5c 88 00 00 00 04 ff ff ff fe 00 00 00 0a"
    "00 00 00 16 76 72 70 6e 5f 54 72 61 63 6b 65 72 20 50 6f 73 5f 51 75 61 74 00 00 00 00 00 00 00";

// S->C Button States, sender 2 (Button0), type 19, seq 31: n=2, states 1 1; padding is "trol".
inline constexpr std::string_view kButtonStates =
    "00 00 00 24 6b 02 29 33 00 04 a8 47 00 00 00 02 00 00 00 13 00 00 00 1f"
    "00 00 00 02 00 00 00 01 00 00 00 01 74 72 6f 6c";

// S->C Pos_Quat, sender 1 (Tracker0), type 4, seq 3: sensor 0, pos 0, quat (0, 0.8925, 0, 0.4510).
inline constexpr std::string_view kPosQuat =
    "00 00 00 58 6b 02 29 12 00 0b ce a6 00 00 00 01 00 00 00 04 00 00 00 03"
    "00 00 00 00 00 00 00 00"
    "00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00"
    "00 00 00 00 00 00 00 00"
    "3f ec 8f 7d a5 52 6f 2d 00 00 00 00 00 00 00 00 3f dc dd 71 5b 5d 99 22";
// Its quaternion y and w exactly (shortest decimal forms of the captured doubles).
inline constexpr double kPosQuatY = 0.8925159672685133;
inline constexpr double kPosQuatW = 0.45101579592155094;

// C->S ping (sender 1 Tracker0, type 16, seq 31) and S->C pong (sender 1, type 17, seq 101).
inline constexpr std::string_view kPing = "00 00 00 18 6b 02 29 34 00 0c 85 51 00 00 00 01 00 00 00 10 00 00 00 1f";
inline constexpr std::string_view kPong = "00 00 00 18 6b 02 29 34 00 0c 89 8e 00 00 00 01 00 00 00 11 00 00 00 65";

// C->S Plane from sphere_client's startSurface: sender 1 (Phantom0), type 6, seq 58; plane
// (0, 1, 0, 100), kspring 1, kdamp 0, fdyn 0.05, fstat 0.1, plane_index 0, n_rec_cycles 10.
inline constexpr std::string_view kPlane =
    "00 00 00 40 6b 02 29 3b 00 0c d7 b7 00 00 00 01 00 00 00 06 00 00 00 3a"
    "00 00 00 00 3f 80 00 00 00 00 00 00 42 c8 00 00"
    "3f 80 00 00 00 00 00 00 3d 4c cc cd 3d cc cc cd"
    "00 00 00 00 00 00 00 0a";

}  // namespace thx::vrpn::transcript
