#pragma once
// Device addresses and the UDP connection request (docs/vrpn.md §1).
//
// Address: "Name@location". The device (sender) name is everything before the FIRST '@', the
// location everything after the LAST '@'. Locations we accept:
//   host | host:port | x-vrpn://host:port   -> mode A, "UDP lob" (the default)
//   tcp://host:port | tcp:host:port         -> mode B, direct TCP (TCP-only link)
// The port is the number after the last ':' (1..65535), 3883 when absent. file: and x-vrsh:
// locations are refused. Hosts are not resolved here.
//
// Lob request (mode A): a UDP datagram "<client-ip> <client-tcp-port>" + NUL. The server
// checks it like the stock one: a host of alphanumerics and dots, one space, a decimal port
// >= 1024; it then connects back to the datagram's SOURCE address at that port (the host text is
// only checked, never used). Datagrams over kMaxLobRequest bytes (NUL included) are refused.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "device/vrpn/error.hpp"

namespace thx::vrpn {

inline constexpr std::uint16_t kDefaultPort = 3883;
inline constexpr std::size_t kMaxLobRequest = 256;

enum class ConnectMode { kUdpLob, kTcp };

struct DeviceAddress {
  std::string device;
  std::string host;
  std::uint16_t port = kDefaultPort;
  ConnectMode mode = ConnectMode::kUdpLob;
  bool operator==(const DeviceAddress&) const = default;
};

Result<DeviceAddress> parseDeviceAddress(std::string_view text);

struct LobRequest {
  std::string host;  // as written by the client; informational
  std::uint16_t port = 0;
  bool operator==(const LobRequest&) const = default;
};

// "ip port\0" (strlen + 1 bytes).
std::vector<std::uint8_t> encodeLobRequest(std::string_view ip, std::uint16_t port);
Result<LobRequest> parseLobRequest(std::span<const std::uint8_t> datagram);

}  // namespace thx::vrpn
