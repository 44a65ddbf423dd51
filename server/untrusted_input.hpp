#pragma once
// Bytes from clients (THX_SUBSCRIBE, THX_HEARTBEAT, THX_COMMAND, THX_CLIENT_FORCE): decode them safely, say
// what is wrong with the ones that do not decode, and log that on stderr without flooding it.
//
// Used by the receiver thread's LCM callbacks (server/receiver.*, server/subscription_inbox.*),
// never by the servo. Depends on the thx_msgs types and the standard library.
#include <cinttypes>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <thx_msgs/protocol.hpp>

namespace thx::srv {

// Decodes `size` bytes into `out` with thx_msgs::try_decode. Returns "" when the bytes are one
// whole message of type T, else what is wrong with them (names the type, sizes, fingerprints):
// shorter than a fingerprint, a wrong type fingerprint, corrupt or truncated content, or bytes
// beyond the end of the message (an oversized datagram is refused, not half-read).
template <class T>
std::string decodeUntrusted(const void* data, std::size_t size, T& out) {
  char buf[256];
  const char* type = T::getTypeName();
  if (data == nullptr || size < 8) {
    std::snprintf(buf, sizeof buf, "%zu bytes, too short for a %s (at least 8 bytes of type fingerprint)", size, type);
    return buf;
  }
  const auto* b = static_cast<const std::uint8_t*>(data);
  std::uint64_t fingerprint = 0;
  for (int i = 0; i < 8; ++i) fingerprint = (fingerprint << 8) | b[i];
  const auto expected = static_cast<std::uint64_t>(T::getHash());
  if (fingerprint != expected) {
    std::snprintf(buf, sizeof buf, "wrong type fingerprint 0x%016" PRIx64 " (%zu bytes): expected a %s, 0x%016" PRIx64,
                  fingerprint, size, type, expected);
    return buf;
  }
  const int n = thx_msgs::try_decode(data, size, out);
  if (n < 0) {
    std::snprintf(buf, sizeof buf,
                  "malformed %s (%zu bytes): truncated, or a string length or count outside the message", type, size);
    return buf;
  }
  if (std::size_t(n) != size) {
    std::snprintf(buf, sizeof buf, "oversized %s: %zu bytes received, the message it holds is %d bytes", type, size, n);
    return buf;
  }
  return {};
}

// One "hapticd: warning: ignored a message on CHANNEL: PROBLEM" line per problem, at most
// `burst` lines per channel in each `interval_ns`; the next line shown says how many were not;
// flush() (and the destructor) reports the rest. Single-threaded: the receiver thread.
class InputProblemLog {
 public:
  explicit InputProblemLog(int burst = 8, std::int64_t interval_ns = 1'000'000'000)
      : burst_(burst), interval_ns_(interval_ns) {}
  ~InputProblemLog() { flush(); }
  InputProblemLog(const InputProblemLog&) = delete;
  InputProblemLog& operator=(const InputProblemLog&) = delete;

  void report(const char* channel, const std::string& problem, std::int64_t now_ns);
  void flush();
  std::uint64_t total() const { return total_; }

 private:
  struct PerChannel {
    std::string channel;
    std::int64_t window_start_ns = 0;
    int shown_in_window = 0;
    std::uint64_t unshown = 0;
    bool used = false;
  };
  PerChannel* find(const char* channel);

  int burst_;
  std::int64_t interval_ns_;
  PerChannel channels_[4];  // the client -> server channels
  std::uint64_t total_ = 0;
};

}  // namespace thx::srv
