#pragma once
// Which udpm ports hapticd uses beside its bus (--lcm-url), from --control-port and --data-ports
// (docs/clients.md §6). The bus carries what every client needs (hellos, replies); the control
// port, which only hapticd listens on, takes what clients send (requests, heartbeats, commands,
// forces); each client's streams go to a data port of its own. All on the bus's multicast group
// with its query (ttl, recv_buf_size). Defaults, for a bus on port P: control P+1, data ports
// P+2 .. P+1+max_clients. A URL that is not udpm:// keeps everything on the bus.
#include <optional>
#include <string>

#include "server/udpm_url.hpp"

namespace thx::srv {

struct PortPlan {
  std::optional<UdpmUrl> bus;  // nullopt: not udpm, everything on the one URL
  int control_port = 0;        // 0: none (clients send to the bus)
  int data_first = 0, data_last = 0;  // data_first 0: none (streams on the bus)

  std::string controlUrl() const { return control_port > 0 ? bus->withPort(control_port) : std::string(); }
};

// control_spec / data_spec: "" (the default), "off", or a port / "FIRST-LAST". Throws
// thx::UsageError naming the option, the value and what was expected: a malformed value, a port
// outside 1..65535, a range that holds the bus or control port, or one of them given explicitly
// with a URL that is not udpm://.
PortPlan planPorts(const std::string& lcm_url, int max_clients, const std::string& control_spec,
                   const std::string& data_spec);

}  // namespace thx::srv
