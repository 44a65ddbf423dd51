#pragma once
// Helpers for driving Endpoints in tests: fixed clocks, stock-like message builders, event
// summaries that compare as strings, and an in-memory pipe between two endpoints.
#include <algorithm>
#include <cstdio>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "tests/vrpn/message_body.hpp"
#include "device/vrpn/endpoint.hpp"
#include "device/vrpn/system_messages.hpp"

namespace thx::vrpn::harness {

using Bytes = std::vector<std::uint8_t>;

inline Endpoint::Options fixedClock(TimeValue t = TimeValue{100, 200}) {
  Endpoint::Options o;
  o.now = [t] { return t; };
  return o;
}

inline Bytes message(std::int32_t sender, std::int32_t type, std::span<const std::uint8_t> payload,
                     std::uint32_t seq = 0) {
  Bytes out;
  appendFrame(out, Header{0, TimeValue{7, 8}, sender, type, seq}, payload);
  return out;
}

inline Bytes description(std::int32_t kind, std::int32_t id, std::string_view name) {
  Bytes body;
  encodeDescription(name, body);
  return message(id, kind, body);
}

inline Bytes senderDesc(std::int32_t id, std::string_view name) { return description(kSenderDescription, id, name); }
inline Bytes typeDesc(std::int32_t id, std::string_view name) { return description(kTypeDescription, id, name); }

using thx::vrpn::test::body;

inline std::string hexOf(std::span<const std::uint8_t> b) {
  std::string s;
  char buf[4];
  for (std::uint8_t x : b) {
    std::snprintf(buf, sizeof buf, "%02x", x);
    s += buf;
  }
  return s;
}

inline std::string summary(const Event& e) {
  if (const auto* c = std::get_if<Connected>(&e))
    return "connected log=" + std::to_string(c->peer.log_mode) +
           " minor_differs=" + std::to_string(c->peer.minor_differs);
  if (const auto* d = std::get_if<Dropped>(&e)) return "dropped " + std::string(toString(d->error.code));
  const auto& m = std::get<UserMessage>(e);
  return "msg " + std::string(m.sender_name) + "/" + std::string(m.type_name) + " ids " + std::to_string(m.sender) +
         "/" + std::to_string(m.type) + " seq " + std::to_string(m.header.sequence) + " t " +
         std::to_string(m.header.time.sec) + "." + std::to_string(m.header.time.usec) + " " + hexOf(m.payload);
}

inline void drainInto(Endpoint& e, std::vector<std::string>& events) {
  while (auto ev = e.poll()) events.push_back(summary(*ev));
}

// Feeds `bytes` cut at `cuts` (ascending), draining after each piece.
inline std::vector<std::string> feedInChunks(Endpoint& e, std::span<const std::uint8_t> bytes,
                                             const std::vector<std::size_t>& cuts = {}) {
  std::vector<std::string> events;
  std::size_t begin = 0;
  for (std::size_t cut : cuts) {
    e.feed(bytes.subspan(begin, cut - begin));
    drainInto(e, events);
    begin = cut;
  }
  e.feed(bytes.subspan(begin));
  drainInto(e, events);
  return events;
}

// Moves everything each side has queued to the other, `chunk` bytes at a time, until both are
// quiet; returns the events each side saw.
struct PipeEvents {
  std::vector<std::string> a, b;
};
inline void pipe(Endpoint& a, Endpoint& b, PipeEvents& ev, std::size_t chunk = 4096) {
  for (bool moved = true; moved;) {
    moved = false;
    for (auto [from, to, sink] : {std::tuple{&a, &b, &ev.b}, std::tuple{&b, &a, &ev.a}}) {
      while (!from->pendingOutput().empty()) {
        const auto out = from->pendingOutput().first(std::min(chunk, from->pendingOutput().size()));
        to->feed(out);
        from->consumeOutput(out.size());
        drainInto(*to, *sink);
        moved = true;
      }
    }
  }
}

}  // namespace thx::vrpn::harness
