#include "device/vrpn/udp_socket.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace thx::vrpn {

namespace {

Result<sockaddr_in> resolve(std::string_view host, std::uint16_t port) {
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* found = nullptr;
  const std::string h(host);
  const int rc = ::getaddrinfo(h.c_str(), nullptr, &hints, &found);
  if (rc != 0 || !found)
    return Error{ErrorCode::kBadAddress, "cannot resolve host '" + h + "': " + ::gai_strerror(rc)};
  sockaddr_in addr = *reinterpret_cast<const sockaddr_in*>(found->ai_addr);
  ::freeaddrinfo(found);
  addr.sin_port = htons(port);
  return addr;
}

}  // namespace

Result<UniqueFd> bindUdp(std::string_view ip, std::uint16_t port) {
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(port);
  if (::inet_pton(AF_INET, std::string(ip).c_str(), &addr.sin_addr) != 1)
    return Error{ErrorCode::kBadAddress, "UDP address '" + std::string(ip) + "' is not an IPv4 address"};
  UniqueFd fd(::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0));
  if (!fd) return socketError("socket", errno);
  const int one = 1;
  ::setsockopt(fd.get(), SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  if (::bind(fd.get(), reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0)
    return socketError("bind (UDP)", errno);
  return fd;
}

std::optional<Datagram> receiveDatagram(int fd) {
  std::uint8_t buf[kMaxLobRequest + 1];
  sockaddr_in src{};
  socklen_t src_len = sizeof src;
  // MSG_TRUNC makes recvfrom return the real length, so an oversized request is recognised.
  const ssize_t n = ::recvfrom(fd, buf, sizeof buf, MSG_TRUNC, reinterpret_cast<sockaddr*>(&src), &src_len);
  if (n < 0) return std::nullopt;
  Datagram d;
  char ip[INET_ADDRSTRLEN] = {};
  ::inet_ntop(AF_INET, &src.sin_addr, ip, sizeof ip);
  d.source_ip = ip;
  d.oversized = std::size_t(n) > kMaxLobRequest;
  const std::size_t kept = d.oversized ? kMaxLobRequest : std::size_t(n);
  d.bytes.assign(buf, buf + kept);
  return d;
}

Result<bool> sendDatagram(std::string_view host, std::uint16_t port, const std::vector<std::uint8_t>& bytes) {
  Result<sockaddr_in> addr = resolve(host, port);
  if (!addr) return addr.error();
  UniqueFd fd(::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0));
  if (!fd) return socketError("socket", errno);
  const ssize_t n = ::sendto(fd.get(), bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&*addr),
                             sizeof(sockaddr_in));
  if (n != ssize_t(bytes.size())) return socketError("sendto", errno);
  return true;
}

Result<std::string> localAddressTowards(std::string_view host, std::uint16_t port) {
  Result<sockaddr_in> addr = resolve(host, port);
  if (!addr) return addr.error();
  UniqueFd fd(::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0));
  if (!fd) return socketError("socket", errno);
  // connect() on a UDP socket only picks the route and the source address.
  if (::connect(fd.get(), reinterpret_cast<const sockaddr*>(&*addr), sizeof(sockaddr_in)) != 0)
    return socketError("connect (UDP route lookup)", errno);
  sockaddr_in local{};
  socklen_t len = sizeof local;
  if (::getsockname(fd.get(), reinterpret_cast<sockaddr*>(&local), &len) != 0) return socketError("getsockname", errno);
  char ip[INET_ADDRSTRLEN] = {};
  ::inet_ntop(AF_INET, &local.sin_addr, ip, sizeof ip);
  return std::string(ip);
}

}  // namespace thx::vrpn
