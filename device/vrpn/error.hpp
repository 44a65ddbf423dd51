#pragma once
// Typed protocol errors and a small value-or-error result.
//
// Contract: every decoding function of thx::vrpn returns either a value or an Error; none throws
// and none aborts on bad input. An Error means "drop this connection" to the connection owner
// (docs/vrpn.md §4: a malformed message kills the link); `reason` is a one-line human-readable
// explanation for the log, `code` is for programs and tests.
#include <string>
#include <string_view>
#include <utility>
#include <variant>

namespace thx::vrpn {

enum class ErrorCode {
  kBadCookie,       // magic or major version differs from "vrpn: ver. 07."
  kBadLogMode,      // cookie log-mode digit outside '0'..'3'
  kLengthTooSmall,  // header length < 24
  kLengthTooLarge,  // header length > kMaxFrameLength
  kTruncated,       // input ended inside a cookie or message
  kBadDescription,  // sender/type description with an inconsistent or oversized body
  kIdOutOfRange,    // a description defines an id outside [0, kMaxNames)
  kPayloadSize,     // a typed message body of the wrong size
  kBadValue,        // a field value the receiver must reject (negative sensor, > 256 buttons)
  kOutputOverflow,  // the peer stopped reading and our queue for it hit its limit
  kBadAddress,      // a device address we cannot parse or do not support
  kBadLobRequest,   // a UDP connection request that fails the stock server's checks
  kSocket,          // a socket call failed (reason carries the call and strerror)
  kPeerClosed,      // the peer closed the connection cleanly between messages
};

std::string_view toString(ErrorCode code);

struct Error {
  ErrorCode code;
  std::string reason;
};

// A failed socket call: kSocket, the call's name and strerror(err).
Error socketError(std::string_view call, int err);

// Value or Error (std::expected is C++23).
template <class T>
class Result {
 public:
  Result(T value) : v_(std::move(value)) {}      // NOLINT(google-explicit-constructor)
  Result(Error error) : v_(std::move(error)) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return v_.index() == 0; }
  explicit operator bool() const { return ok(); }
  const T& value() const& { return std::get<0>(v_); }
  T& value() & { return std::get<0>(v_); }
  T&& value() && { return std::get<0>(std::move(v_)); }
  const T& operator*() const& { return value(); }
  const T* operator->() const { return &value(); }
  const Error& error() const { return std::get<1>(v_); }

 private:
  std::variant<T, Error> v_;
};

}  // namespace thx::vrpn
