#include "device/vrpn/endpoint.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "device/vrpn/system_messages.hpp"

namespace thx::vrpn {

Endpoint::Endpoint(Options options) : options_(std::move(options)) {
  if (!options_.now) options_.now = wallClockNow;
  senders_.addLocal(kControlSenderName);
  for (std::string_view t : kControlTypeNames) types_.addLocal(t);
  const Cookie cookie = makeCookie(0);
  out_.insert(out_.end(), cookie.begin(), cookie.end());
  stats_.bytes_queued += cookie.size();
}

std::int32_t Endpoint::addSender(std::string_view name) { return addName(senders_, kSenderDescription, name); }
std::int32_t Endpoint::addType(std::string_view name) { return addName(types_, kTypeDescription, name); }

std::int32_t Endpoint::addName(NameMap& map, std::int32_t kind, std::string_view name) {
  const std::int32_t before = map.localCount();
  const std::int32_t id = map.addLocal(name);
  // Before the handshake, queueAllDescriptions() will describe it with the others.
  if (id != kNoId && map.localCount() > before && state_ == State::kConnected)
    queueDescription(kind, id, map.localName(id));
  return id;
}

void Endpoint::feed(std::span<const std::uint8_t> bytes) {
  if (state_ == State::kDropped || input_finished_) return;
  stats_.bytes_in += bytes.size();
  if (peer_cookie_fill_ < kCookieSize) {
    const std::size_t n = std::min(bytes.size(), kCookieSize - peer_cookie_fill_);
    std::copy_n(bytes.begin(), n, peer_cookie_.begin() + std::ptrdiff_t(peer_cookie_fill_));
    peer_cookie_fill_ += n;
    bytes = bytes.subspan(n);
  }
  if (!bytes.empty()) frames_.feed(bytes);
}

std::optional<Event> Endpoint::poll() {
  if (state_ == State::kDropped) {
    if (drop_reported_) return std::nullopt;
    drop_reported_ = true;
    return Dropped{*error_};
  }
  if (state_ == State::kHandshake) {
    if (peer_cookie_fill_ < kCookieSize) {
      if (!input_finished_) return std::nullopt;
      fail(Error{ErrorCode::kTruncated,
                 "peer closed after " + std::to_string(peer_cookie_fill_) + " of 24 cookie bytes"});
      return poll();
    }
    Result<PeerCookie> peer = checkCookie(peer_cookie_);
    if (!peer) {
      fail(peer.error());
      return poll();
    }
    peer_ = *peer;
    state_ = State::kConnected;
    queueAllDescriptions();
    if (state_ == State::kDropped) return poll();  // our own descriptions overflowed the queue
    return Connected{*peer_};
  }
  for (;;) {
    DecodeStep step = frames_.next();
    if (std::holds_alternative<NeedMore>(step)) {
      if (!input_finished_) return std::nullopt;
      std::optional<Error> end = frames_.finish();
      fail(end ? std::move(*end) : Error{ErrorCode::kPeerClosed, "peer closed the connection"});
      return poll();
    }
    if (auto* e = std::get_if<Error>(&step)) {
      fail(std::move(*e));
      return poll();
    }
    const Frame& frame = std::get<Frame>(step);
    ++stats_.messages_in;
    if (frame.header.type < 0) {
      if (auto e = handleSystem(frame)) {
        fail(std::move(*e));
        return poll();
      }
      continue;
    }
    if (!senders_.remoteDescribed(frame.header.sender) || !types_.remoteDescribed(frame.header.type)) {
      ++stats_.skipped_undescribed;
      continue;
    }
    const std::int32_t sender = senders_.toLocal(frame.header.sender);
    const std::int32_t type = types_.toLocal(frame.header.type);
    if (sender == kNoId || type == kNoId) {
      ++stats_.skipped_unknown;
      continue;
    }
    ++stats_.delivered;
    return UserMessage{sender, type, senders_.localName(sender), types_.localName(type), frame.header, frame.payload};
  }
}

std::optional<Error> Endpoint::handleSystem(const Frame& frame) {
  const std::int32_t type = frame.header.type;
  if (type != kSenderDescription && type != kTypeDescription) {
    ++stats_.system_ignored;  // TCP-only and never logging: UDP/LOG descriptions don't concern us
    return std::nullopt;
  }
  Result<std::string_view> name = decodeDescription(frame.payload);
  if (!name) return name.error();
  NameMap& map = type == kSenderDescription ? senders_ : types_;
  Result<bool> defined = map.defineRemote(frame.header.sender, *name);
  if (!defined) return defined.error();
  ++stats_.descriptions_in;
  return std::nullopt;
}

void Endpoint::drop(Error error) { fail(std::move(error)); }

void Endpoint::fail(Error error) {
  if (state_ == State::kDropped) return;
  state_ = State::kDropped;
  error_ = std::move(error);
}

bool Endpoint::send(std::int32_t sender, std::int32_t type, std::span<const std::uint8_t> payload, TimeValue time) {
  if (state_ != State::kConnected) return false;
  if (senders_.localName(sender).empty() || types_.localName(type).empty()) return false;
  return queueFrame(sender, type, payload, time);
}

bool Endpoint::queueFrame(std::int32_t sender, std::int32_t type, std::span<const std::uint8_t> payload,
                          TimeValue time) {
  if (payload.size() > kMaxPayloadLength) return false;
  const std::size_t size = frameSize(payload.size());
  if (pendingOutput().size() + size > options_.max_pending_output) {
    fail(Error{ErrorCode::kOutputOverflow, "peer is not reading: " + std::to_string(pendingOutput().size()) +
                                               " bytes already queued, limit " +
                                               std::to_string(options_.max_pending_output)});
    return false;
  }
  appendFrame(out_, Header{0, time, sender, type, out_sequence_++}, payload);
  ++stats_.messages_out;
  stats_.bytes_queued += size;
  return true;
}

bool Endpoint::queueDescription(std::int32_t kind, std::int32_t id, std::string_view name) {
  scratch_.clear();
  encodeDescription(name, scratch_);
  return queueFrame(id, kind, scratch_, options_.now());
}

void Endpoint::queueAllDescriptions() {
  for (std::int32_t id = 0; id < senders_.localCount(); ++id)
    if (!queueDescription(kSenderDescription, id, senders_.localName(id))) return;
  for (std::int32_t id = 0; id < types_.localCount(); ++id)
    if (!queueDescription(kTypeDescription, id, types_.localName(id))) return;
}

void Endpoint::consumeOutput(std::size_t n) {
  out_pos_ += std::min(n, out_.size() - out_pos_);
  if (out_pos_ == out_.size()) {
    out_.clear();  // keeps the capacity: steady-state sending does not allocate
    out_pos_ = 0;
  } else if (out_pos_ >= 65536 && out_pos_ * 2 >= out_.size()) {
    out_.erase(out_.begin(), out_.begin() + std::ptrdiff_t(out_pos_));
    out_pos_ = 0;
  }
}

}  // namespace thx::vrpn
