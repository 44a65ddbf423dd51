#pragma once
// Where hapticd's udpm traffic goes, said once at start (docs/clients.md §6, "Clients on other
// machines"): the URL's multicast TTL (LCM's default 0 keeps every packet on this host) and the
// interface the kernel's route to the group picks. LCM 1.3.1 has no option to name the
// interface: the multicast route chooses it (`ip route add 224.0.0.0/4 dev eth0`), so this
// reports the route's choice rather than setting one.
#include <string>

namespace thx::srv {

// e.g. "LCM udpm://239.255.76.67:7667?ttl=1: TTL 1, the streams leave this host through eth0
// (10.31.0.1)". "" for a URL that is not udpm (memq://, tcpq://, file://: no multicast).
std::string describeMulticastPath(const std::string& lcm_url);

// The `ttl=N` of a udpm URL's query; 0 (LCM's default) when it names none or N is not 0..255.
int multicastTtl(const std::string& query);

}  // namespace thx::srv
