#include "device/vrpn/error.hpp"

#include <cstring>
#include <string>

namespace thx::vrpn {

std::string_view toString(ErrorCode code) {
  switch (code) {
    case ErrorCode::kBadCookie:
      return "bad cookie";
    case ErrorCode::kBadLogMode:
      return "bad log mode";
    case ErrorCode::kLengthTooSmall:
      return "length too small";
    case ErrorCode::kLengthTooLarge:
      return "length too large";
    case ErrorCode::kTruncated:
      return "truncated";
    case ErrorCode::kBadDescription:
      return "bad description";
    case ErrorCode::kIdOutOfRange:
      return "id out of range";
    case ErrorCode::kPayloadSize:
      return "payload size";
    case ErrorCode::kBadValue:
      return "bad value";
    case ErrorCode::kOutputOverflow:
      return "output overflow";
    case ErrorCode::kBadAddress:
      return "bad address";
    case ErrorCode::kBadLobRequest:
      return "bad lob request";
    case ErrorCode::kSocket:
      return "socket error";
    case ErrorCode::kPeerClosed:
      return "peer closed";
  }
  return "unknown error";
}

Error socketError(std::string_view call, int err) {
  return Error{ErrorCode::kSocket, std::string(call) + ": " + std::strerror(err)};
}

}  // namespace thx::vrpn
