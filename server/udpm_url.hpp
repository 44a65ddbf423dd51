#pragma once
// An LCM udpm URL taken apart, so hapticd can derive the URLs of its control port and of each
// client's data port from --lcm-url: the same multicast group and query (ttl, recv_buf_size),
// another port (docs/clients.md §6). Other providers (memq://, tcpq://, file://) have no ports
// to split traffic over: parseUdpmUrl() returns nullopt for them and hapticd keeps everything on
// the one URL.
#include <optional>
#include <string>

namespace thx::srv {

struct UdpmUrl {
  std::string group;  // e.g. "239.255.76.67"
  int port = 7667;    // LCM's default when the URL names none
  std::string query;  // without the '?', e.g. "ttl=0&recv_buf_size=4194304"; may be empty

  // "udpm://GROUP:PORT?QUERY" with `port` in place of this URL's port.
  std::string withPort(int port) const;
};

// nullopt for a URL that is not udpm://GROUP[:PORT][?QUERY] with a port in 1..65535
// ("udpm://" alone is LCM's default group and port).
std::optional<UdpmUrl> parseUdpmUrl(const std::string& url);

}  // namespace thx::srv
