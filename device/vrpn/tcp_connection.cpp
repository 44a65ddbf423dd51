#include "device/vrpn/tcp_connection.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

namespace thx::vrpn {

namespace {

bool setNonBlocking(int fd) {
  const int flags = ::fcntl(fd, F_GETFL, 0);
  return flags >= 0 && ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) == 0;
}

void setNoDelay(int fd) {
  const int one = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);  // best effort: latency, not correctness
}

bool wouldBlock(int err) { return err == EAGAIN || err == EWOULDBLOCK; }

}  // namespace

UniqueFd& UniqueFd::operator=(UniqueFd&& o) noexcept {
  if (this != &o) {
    reset();
    fd_ = o.release();
  }
  return *this;
}

void UniqueFd::reset() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

Result<UniqueFd> listenTcp(std::string_view ip, std::uint16_t port, int backlog) {
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(port);
  if (::inet_pton(AF_INET, std::string(ip).c_str(), &addr.sin_addr) != 1)
    return Error{ErrorCode::kBadAddress, "listen address '" + std::string(ip) + "' is not an IPv4 address"};
  UniqueFd fd(::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0));
  if (!fd) return socketError("socket", errno);
  const int one = 1;
  ::setsockopt(fd.get(), SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);  // quick restarts of a server
  if (::bind(fd.get(), reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) return socketError("bind", errno);
  if (::listen(fd.get(), backlog) != 0) return socketError("listen", errno);
  if (!setNonBlocking(fd.get())) return socketError("fcntl", errno);
  return fd;
}

Result<UniqueFd> acceptTcp(int listen_fd) {
  for (;;) {
    UniqueFd fd(::accept4(listen_fd, nullptr, nullptr, SOCK_CLOEXEC));
    if (fd) return fd;
    if (errno == EINTR || errno == ECONNABORTED) continue;
    if (wouldBlock(errno)) return UniqueFd{};
    return socketError("accept", errno);
  }
}

std::string peerName(int fd) {
  sockaddr_in addr{};
  socklen_t len = sizeof addr;
  if (::getpeername(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0 || addr.sin_family != AF_INET) return "?";
  char ip[INET_ADDRSTRLEN] = {};
  ::inet_ntop(AF_INET, &addr.sin_addr, ip, sizeof ip);
  return std::string(ip) + ":" + std::to_string(ntohs(addr.sin_port));
}

void capSendBuffer(int fd, int bytes) { ::setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &bytes, sizeof bytes); }

Result<UniqueFd> connectTcp(std::string_view host, std::uint16_t port) {
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_NUMERICSERV;
  addrinfo* found = nullptr;
  const std::string service = std::to_string(port);
  if (const int rc = ::getaddrinfo(std::string(host).c_str(), service.c_str(), &hints, &found); rc != 0)
    return Error{ErrorCode::kBadAddress, "cannot resolve '" + std::string(host) + "': " + ::gai_strerror(rc)};
  sockaddr_in addr{};
  std::memcpy(&addr, found->ai_addr, sizeof addr);
  ::freeaddrinfo(found);

  UniqueFd fd(::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0));
  if (!fd) return socketError("socket", errno);
  if (::connect(fd.get(), reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0 && errno != EINPROGRESS)
    return socketError("connect", errno);
  return fd;
}

std::uint16_t localPort(int fd) {
  sockaddr_in addr{};
  socklen_t len = sizeof addr;
  if (::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) return 0;
  return ntohs(addr.sin_port);
}

TcpConnection::TcpConnection(UniqueFd fd, Endpoint::Options options)
    : fd_(std::move(fd)), endpoint_(std::move(options)) {
  if (!fd_) {
    close(Error{ErrorCode::kSocket, "no socket"});
    return;
  }
  if (!setNonBlocking(fd_.get())) {
    close(socketError("fcntl", errno));
    return;
  }
  setNoDelay(fd_.get());
}

void TcpConnection::close(Error reason) {
  if (!open()) return;
  endpoint_.drop(reason);  // no-op if the endpoint already dropped with its own reason
  close_reason_ = endpoint_.error() ? *endpoint_.error() : std::move(reason);
  fd_.reset();
}

bool TcpConnection::pump() {
  if (!open()) return false;
  // A protocol error or end of input reached through the owner's poll(): the link is finished.
  if (endpoint_.state() == Endpoint::State::kDropped) {
    close(*endpoint_.error());
    return false;
  }
  return writeSome() && readSome();
}

bool TcpConnection::writeSome() {
  while (!endpoint_.pendingOutput().empty()) {
    const auto out = endpoint_.pendingOutput();
    const ssize_t n = ::send(fd_.get(), out.data(), out.size(), MSG_NOSIGNAL);
    if (n > 0) {
      endpoint_.consumeOutput(std::size_t(n));
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && wouldBlock(errno)) return true;  // full, or still connecting
    close(socketError("send", n < 0 ? errno : EPIPE));
    return false;
  }
  return true;
}

bool TcpConnection::readSome() {
  // One scratch buffer per thread, not per connection: the endpoint copies what it is fed.
  static thread_local std::vector<std::uint8_t> buffer(kReadChunk);
  std::size_t total = 0;
  while (total < kMaxReadPerPump) {
    const ssize_t n = ::recv(fd_.get(), buffer.data(), buffer.size(), 0);
    if (n > 0) {
      endpoint_.feed(std::span(buffer).first(std::size_t(n)));
      total += std::size_t(n);
      continue;
    }
    // A reset is how a peer's close reaches us when it still had our data unread (a stock client
    // exiting while 1 kHz reports were in flight): the peer is gone as after an orderly close.
    if (n == 0 || (n < 0 && errno == ECONNRESET)) {
      // The endpoint reports the end in stream order, after what was already fed; the socket
      // is done now.
      endpoint_.finishInput();
      close_reason_ = Error{ErrorCode::kPeerClosed, n == 0 ? "peer closed the connection" : "peer reset the connection"};
      fd_.reset();
      return false;
    }
    if (errno == EINTR) continue;
    if (wouldBlock(errno)) return true;
    close(socketError("recv", errno));
    return false;
  }
  return true;
}

}  // namespace thx::vrpn
