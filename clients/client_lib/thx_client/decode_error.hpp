#pragma once
// What a subscriber reports when bytes on one of its channels do not decode as the type it
// expects (a corrupt datagram, another program's type on our channel, an old protocol version).
// The subscriber drops the bytes and keeps running; the error callback decides what to say.
#include <cstddef>
#include <functional>
#include <string>

namespace thx::client {

struct DecodeError {
  std::string channel;
  std::string expected_type;  // e.g. "physics_poses_t"
  std::size_t bytes = 0;
  // "THX_PHYSICS_POSES: 12 bytes that do not decode as physics_poses_t"
  std::string message() const {
    return channel + ": " + std::to_string(bytes) + " bytes that do not decode as " + expected_type;
  }
};
using DecodeErrorHandler = std::function<void(const DecodeError&)>;

}  // namespace thx::client
