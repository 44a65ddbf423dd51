#pragma once
// UDP for the connection request of mode A ("UDP lob", docs/vrpn.md §1): the server's request
// socket and the client's request datagram. With tcp_connection.hpp, the only files in thx_vrpn
// that touch sockets. IPv4 only; nothing here blocks except name resolution (getaddrinfo) in
// sendDatagram() and localAddressTowards(), which belong on I/O threads.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "device/vrpn/addressing.hpp"
#include "device/vrpn/error.hpp"
#include "device/vrpn/tcp_connection.hpp"

namespace thx::vrpn {

// A non-blocking UDP socket bound to ip:port (the server binds its TCP port number, §1).
Result<UniqueFd> bindUdp(std::string_view ip, std::uint16_t port);

struct Datagram {
  std::string source_ip;             // dotted quad of the sender
  std::vector<std::uint8_t> bytes;   // at most kMaxLobRequest bytes
  bool oversized = false;            // it was longer than kMaxLobRequest (bytes then truncated)
};
// The next queued datagram, or nothing when none is waiting (or on a socket error).
std::optional<Datagram> receiveDatagram(int fd);

// Sends `bytes` to host:port from a fresh ephemeral socket.
Result<bool> sendDatagram(std::string_view host, std::uint16_t port, const std::vector<std::uint8_t>& bytes);

// The local IPv4 address the kernel would use to reach host:port (no packet is sent): where a
// mode-A client binds its connect-back listener.
Result<std::string> localAddressTowards(std::string_view host, std::uint16_t port);

}  // namespace thx::vrpn
