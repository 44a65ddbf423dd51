#pragma once
// VRPN device addresses as stock VRPN clients write them: "Device@host", "Device@host:port" or
// "Device@tcp://host:port" (docs/vrpn.md §1). Checked at load time so a
// malformed address is reported with its line instead of as a connection that never happens.
#include <optional>
#include <string>

namespace thx::scene {

struct VrpnAddress {
  std::string device;  // "Phantom0"
  std::string scheme;  // "" or "tcp"
  std::string host;    // "localhost"
  int port = 3883;     // VRPN's default port when none is given
};

inline constexpr int kVrpnDefaultPort = 3883;

// nullopt (and `problem` set) if malformed.
std::optional<VrpnAddress> parseVrpnAddress(const std::string& text, std::string* problem = nullptr);

}  // namespace thx::scene
