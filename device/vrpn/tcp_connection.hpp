#pragma once
// Non-blocking TCP transport for one Endpoint. Sockets live here and nowhere else in thx_vrpn;
// all protocol decisions stay in Endpoint, which this class only feeds and drains.
//
// Contract:
//  - The constructor takes ownership of a connected (or connecting) socket, makes it
//    non-blocking, sets TCP_NODELAY (the stock server does too) and MSG_NOSIGNAL is used on every
//    send, so a dead peer never raises SIGPIPE.
//  - pump() never blocks: it writes what the endpoint has queued, then reads at most
//    kMaxReadPerPump bytes into it (bounding memory per round), and reports whether the
//    connection is still open. Drain endpoint().poll() after each pump(); the endpoint keeps
//    unpolled input across pumps.
//  - The connection closes itself (and closes the fd) on the first of: the endpoint dropped
//    (protocol error), a socket error, or the peer's EOF; closeReason() says which. The endpoint
//    always ends with a Dropped event: on a socket error at once, on EOF (or a reset: a peer that
//    closed with our data unread) after the messages that arrived before it (kPeerClosed, or
//    kTruncated if the peer stopped mid-message).
//  - Waiting is the owner's business: poll(2) on fd() for POLLIN, plus POLLOUT when wantsWrite().
// IPv4 only. connectTcp() resolves names with getaddrinfo, which may block: call it outside the
// servo thread.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "device/vrpn/endpoint.hpp"
#include "device/vrpn/error.hpp"

namespace thx::vrpn {

// Owns a file descriptor; closes it once.
class UniqueFd {
 public:
  UniqueFd() = default;
  explicit UniqueFd(int fd) : fd_(fd) {}
  UniqueFd(UniqueFd&& o) noexcept : fd_(o.release()) {}
  UniqueFd& operator=(UniqueFd&& o) noexcept;
  UniqueFd(const UniqueFd&) = delete;
  UniqueFd& operator=(const UniqueFd&) = delete;
  ~UniqueFd() { reset(); }
  int get() const { return fd_; }
  int release() {
    const int fd = fd_;
    fd_ = -1;
    return fd;
  }
  void reset();
  explicit operator bool() const { return fd_ >= 0; }

 private:
  int fd_ = -1;
};

// A non-blocking listening socket on ip:port (port 0 = ephemeral; see localPort()).
Result<UniqueFd> listenTcp(std::string_view ip, std::uint16_t port, int backlog = 16);
// The next pending connection, or an empty UniqueFd when none is waiting.
Result<UniqueFd> acceptTcp(int listen_fd);
// Starts a non-blocking connect to host:port; the connection completes in the background.
Result<UniqueFd> connectTcp(std::string_view host, std::uint16_t port);
std::uint16_t localPort(int fd);
// "ip:port" of the connected peer (for log lines), or "?" when unknown.
std::string peerName(int fd);
// Caps the kernel's send buffer for `fd` (SO_SNDBUF; Linux doubles the value and stops
// autotuning it). Best effort. A server streaming reports uses it so that a slow reader's
// backlog builds up in the server's queue, where reports can be skipped, instead of in megabytes
// of kernel buffer that it would read seconds late.
void capSendBuffer(int fd, int bytes);

class TcpConnection {
 public:
  static constexpr std::size_t kReadChunk = 64 * 1024;
  static constexpr std::size_t kMaxReadPerPump = 4 * kReadChunk;

  explicit TcpConnection(UniqueFd fd, Endpoint::Options options = {});

  Endpoint& endpoint() { return endpoint_; }
  const Endpoint& endpoint() const { return endpoint_; }

  // One non-blocking round of writing and reading; false once the connection is closed.
  bool pump();
  bool open() const { return fd_.get() >= 0; }
  int fd() const { return fd_.get(); }
  bool wantsWrite() const { return open() && !endpoint_.pendingOutput().empty(); }
  // Why it closed (nothing while open).
  const std::optional<Error>& closeReason() const { return close_reason_; }
  // Closes now (e.g. the owner shuts down); the reason is recorded.
  void close(Error reason);

 private:
  bool writeSome();
  bool readSome();

  UniqueFd fd_;
  Endpoint endpoint_;
  std::optional<Error> close_reason_;
};

}  // namespace thx::vrpn
