#include "server/multicast_path.hpp"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <string>

#include "server/udpm_url.hpp"

namespace thx::srv {

namespace {

// The interface holding IPv4 address `a`, or "" when none does.
std::string interfaceOf(in_addr a) {
  ifaddrs* all = nullptr;
  if (getifaddrs(&all) != 0) return "";
  std::string name;
  for (const ifaddrs* i = all; i && name.empty(); i = i->ifa_next) {
    if (!i->ifa_addr || i->ifa_addr->sa_family != AF_INET) continue;
    if (reinterpret_cast<const sockaddr_in*>(i->ifa_addr)->sin_addr.s_addr == a.s_addr) name = i->ifa_name;
  }
  freeifaddrs(all);
  return name;
}

}  // namespace

int multicastTtl(const std::string& query) {
  std::size_t at = 0;
  while (at < query.size()) {
    const std::size_t end = std::min(query.find('&', at), query.size());
    const std::string pair = query.substr(at, end - at);
    if (pair.rfind("ttl=", 0) == 0) {
      const std::string v = pair.substr(4);
      if (v.empty() || v.size() > 3 || v.find_first_not_of("0123456789") != std::string::npos) return 0;
      const int ttl = std::stoi(v);
      return ttl <= 255 ? ttl : 0;
    }
    at = end + 1;
  }
  return 0;
}

std::string describeMulticastPath(const std::string& lcm_url) {
  const std::optional<UdpmUrl> url = parseUdpmUrl(lcm_url);
  if (!url) return "";
  const int ttl = multicastTtl(url->query);
  std::string line = "LCM " + lcm_url + ": TTL " + std::to_string(ttl);
  // A UDP socket "connected" to the group sends nothing; the kernel only picks the route, whose
  // source address names the interface.
  sockaddr_in group{};
  group.sin_family = AF_INET;
  group.sin_port = htons(static_cast<std::uint16_t>(url->port));
  if (inet_pton(AF_INET, url->group.c_str(), &group.sin_addr) != 1) {
    return line + ", group " + url->group + " is not an IPv4 address";
  }
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) return line + ", route unknown (socket: " + std::strerror(errno) + ")";
  std::string where;
  sockaddr_in local{};
  socklen_t length = sizeof local;
  if (connect(fd, reinterpret_cast<const sockaddr*>(&group), sizeof group) != 0) {
    where = ", no route to " + url->group + " (" + std::strerror(errno) + ")";
  } else if (getsockname(fd, reinterpret_cast<sockaddr*>(&local), &length) == 0) {
    char address[INET_ADDRSTRLEN] = "?";
    inet_ntop(AF_INET, &local.sin_addr, address, sizeof address);
    const std::string name = interfaceOf(local.sin_addr);
    where = std::string(ttl == 0 ? ", the streams stay on this host" : ", the streams leave this host") + " through " +
            (name.empty() ? std::string("the interface of ") : name + " (") + address + (name.empty() ? "" : ")");
  }
  close(fd);
  return line + where;
}

}  // namespace thx::srv
