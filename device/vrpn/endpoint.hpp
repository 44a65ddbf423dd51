#pragma once
// Endpoint: one VRPN connection's protocol state, without sockets. The owner moves bytes: it
// feed()s what it read, drains poll() for events, and writes pendingOutput() to the peer. That
// keeps the whole protocol drivable byte by byte in tests.
//
// Handshake (docs/vrpn.md §2, §3): the constructor queues our cookie (log mode 0). Once the peer's
// 24 cookie bytes are in and pass checkCookie, we queue a description of every local sender (id
// order) and then every local type (id order) and poll() returns Connected. We are TCP-only: we
// never send a UDP_DESCRIPTION or LOG_DESCRIPTION, and ignore the peer's.
//
// Names (docs/vrpn.md §5): addSender/addType register local names (idempotent, stable ids; sender 0
// "VRPN Control" and types 0..3 are pre-registered like a stock peer's). A name added after the
// handshake is described at once. Peer descriptions are accepted at any time, echoes included;
// peer ids are mapped to ours by name.
//
// poll() returns, in stream order:
//  - Connected once, after the peer's cookie;
//  - UserMessage for a message whose sender and type the peer described AND we registered; the
//    rest is skipped and counted (undescribed ids: docs/vrpn.md §4; names we don't know: "unknown
//    types skipped"). Sequence words and padding are ignored. The payload (and the name views)
//    stay valid until the next feed();
//  - Dropped once, on the first error (bad cookie, malformed frame or description, output
//    overflow, drop()) or at the end of input (finishInput); afterwards feed()/send() do nothing
//    and poll() returns nothing. The owner closes this connection only.
// Drain poll() until it returns nothing after every feed(): the input buffer holds what was fed
// and not yet polled.
//
// Sending: send() returns false (and queues nothing) before Connected, after Dropped, or for ids
// we never registered. If the peer stops reading and the queue would exceed max_pending_output,
// the endpoint drops (kOutputOverflow). Sequence numbers count every message we send, from 0.
// Not thread-safe; no call blocks.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string_view>
#include <variant>
#include <vector>

#include "device/vrpn/byte_io.hpp"
#include "device/vrpn/cookie.hpp"
#include "device/vrpn/error.hpp"
#include "device/vrpn/frame_decoder.hpp"
#include "device/vrpn/header.hpp"
#include "device/vrpn/limits.hpp"
#include "device/vrpn/name_map.hpp"

namespace thx::vrpn {

struct Connected {
  PeerCookie peer;
};

struct UserMessage {
  std::int32_t sender = kNoId;  // our ids
  std::int32_t type = kNoId;
  std::string_view sender_name;
  std::string_view type_name;
  Header header;  // as received: the peer's ids, time, sequence
  std::span<const std::uint8_t> payload;
};

struct Dropped {
  Error error;
};

using Event = std::variant<Connected, UserMessage, Dropped>;

struct EndpointStats {
  std::uint64_t bytes_in = 0;
  std::uint64_t bytes_queued = 0;  // cookie included
  std::uint64_t messages_in = 0;   // every whole message, system ones included
  std::uint64_t messages_out = 0;
  std::uint64_t delivered = 0;            // UserMessage events
  std::uint64_t descriptions_in = 0;      // including echoes
  std::uint64_t skipped_undescribed = 0;  // the peer never described the sender or type id
  std::uint64_t skipped_unknown = 0;      // described, but a name we did not register
  std::uint64_t system_ignored = 0;       // UDP/LOG descriptions, DISCONNECT, unknown system types
};

class Endpoint {
 public:
  using TimeSource = std::function<TimeValue()>;
  struct Options {
    std::size_t max_pending_output = kDefaultMaxPendingOutput;
    TimeSource now = wallClockNow;  // stamps the descriptions and send() without a time
  };

  enum class State { kHandshake, kConnected, kDropped };

  Endpoint() : Endpoint(Options{}) {}
  explicit Endpoint(Options options);

  // Our id for the name (registering it), or kNoId for an invalid name or a full table.
  std::int32_t addSender(std::string_view name);
  std::int32_t addType(std::string_view name);
  std::int32_t senderId(std::string_view name) const { return senders_.findLocal(name); }
  std::int32_t typeId(std::string_view name) const { return types_.findLocal(name); }
  const NameMap& senders() const { return senders_; }
  const NameMap& types() const { return types_; }

  void feed(std::span<const std::uint8_t> bytes);
  std::optional<Event> poll();
  // The peer closed its side (no feed() after this): poll() still returns what was fed, then
  // Dropped with kPeerClosed, or kTruncated if the input stopped inside the cookie or a message.
  void finishInput() { input_finished_ = true; }
  // The owner's verdict (e.g. a typed body failed to decode): drop with this reason.
  void drop(Error error);

  bool send(std::int32_t sender, std::int32_t type, std::span<const std::uint8_t> payload, TimeValue time);
  bool send(std::int32_t sender, std::int32_t type, std::span<const std::uint8_t> payload) {
    return send(sender, type, payload, options_.now());
  }
  // Encodes a message struct (base/tracker/button/force_messages.hpp), registering its type name.
  template <class M>
  bool sendMessage(std::int32_t sender, const M& message, std::optional<TimeValue> time = std::nullopt) {
    const std::int32_t type = addType(M::kTypeName);
    scratch_.clear();
    ByteWriter w(scratch_);
    message.encode(w);
    return send(sender, type, scratch_, time ? *time : options_.now());
  }

  std::span<const std::uint8_t> pendingOutput() const { return std::span(out_).subspan(out_pos_); }
  void consumeOutput(std::size_t n);

  State state() const { return state_; }
  const std::optional<Error>& error() const { return error_; }
  const std::optional<PeerCookie>& peer() const { return peer_; }
  const EndpointStats& stats() const { return stats_; }

 private:
  void fail(Error error);
  bool queueFrame(std::int32_t sender, std::int32_t type, std::span<const std::uint8_t> payload, TimeValue time);
  bool queueDescription(std::int32_t kind, std::int32_t id, std::string_view name);
  void queueAllDescriptions();
  std::optional<Error> handleSystem(const Frame& frame);
  std::int32_t addName(NameMap& map, std::int32_t kind, std::string_view name);

  Options options_;
  State state_ = State::kHandshake;
  std::optional<Error> error_;
  bool drop_reported_ = false;
  bool input_finished_ = false;

  Cookie peer_cookie_{};
  std::size_t peer_cookie_fill_ = 0;
  std::optional<PeerCookie> peer_;
  FrameDecoder frames_;

  NameMap senders_;
  NameMap types_;

  std::vector<std::uint8_t> out_;
  std::size_t out_pos_ = 0;
  std::uint32_t out_sequence_ = 0;
  std::vector<std::uint8_t> scratch_;

  EndpointStats stats_;
};

}  // namespace thx::vrpn
