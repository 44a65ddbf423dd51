#pragma once
// One fuzzing step for the VRPN decoder, shared by the libFuzzer target (fuzz/) and the short
// deterministic run in test_fuzz_decoder.cpp. Returns a description of the first broken invariant,
// or nothing. Memory errors and UB are left to ASan/UBSan to catch.
//
// Input: byte 0 picks the mode (bit 0: prepend a valid cookie, so the fuzzer reaches the message
// path at once; bits 1..7: seed of the chunking), the rest is the peer's byte stream.
// Invariants:
//  1. the Endpoint gives the same events whether the stream arrives whole or in random chunks;
//  2. nothing follows a Dropped event;
//  3. every delivered message whose typed decode succeeds re-encodes to bytes that decode and
//     re-encode to themselves (encode . decode is a projection), at the size it arrived with when
//     the type has a fixed size;
//  4. the bare FrameDecoder agrees with itself across chunkings too;
//  5. the typed decoders and the addressing parsers survive the raw bytes.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "device/vrpn/addressing.hpp"
#include "device/vrpn/base_messages.hpp"
#include "device/vrpn/button_messages.hpp"
#include "device/vrpn/force_messages.hpp"
#include "device/vrpn/tracker_messages.hpp"
#include "device/vrpn/tracker_transform_messages.hpp"
#include "tests/vrpn/endpoint_harness.hpp"

namespace thx::vrpn::fuzz {

using Failure = std::optional<std::string>;

template <class M>
Failure roundTrip(std::span<const std::uint8_t> payload) {
  Result<M> first = M::decode(payload);
  if (!first) {
    if (first.error().reason.empty()) return std::string(M::kTypeName) + ": error without a reason";
    return std::nullopt;
  }
  const harness::Bytes b1 = harness::body(*first);
  Result<M> second = M::decode(b1);
  if (!second) return std::string(M::kTypeName) + ": re-encoded body does not decode: " + second.error().reason;
  if (harness::body(*second) != b1) return std::string(M::kTypeName) + ": encode(decode(x)) is not stable";
  if constexpr (requires { M::kSize; }) {
    if (b1.size() != payload.size()) return std::string(M::kTypeName) + ": fixed-size body changed size";
  }
  return std::nullopt;
}

using Checker = Failure (*)(std::span<const std::uint8_t>);
struct TypedChecker {
  std::string_view name;
  Checker check;
};
inline constexpr TypedChecker kCheckers[] = {
    {Ping::kTypeName, &roundTrip<Ping>},
    {Pong::kTypeName, &roundTrip<Pong>},
    {TextMessage::kTypeName, &roundTrip<TextMessage>},
    {TrackerPosQuat::kTypeName, &roundTrip<TrackerPosQuat>},
    {TrackerVelocity::kTypeName, &roundTrip<TrackerVelocity>},
    {TrackerUpdateRate::kTypeName, &roundTrip<TrackerUpdateRate>},
    {TrackerResetOrigin::kTypeName, &roundTrip<TrackerResetOrigin>},
    {TrackerToRoom::kTypeName, &roundTrip<TrackerToRoom>},
    {TrackerUnitToSensor::kTypeName, &roundTrip<TrackerUnitToSensor>},
    {TrackerWorkspace::kTypeName, &roundTrip<TrackerWorkspace>},
    {TrackerRequestToRoom::kTypeName, &roundTrip<TrackerRequestToRoom>},
    {TrackerRequestUnitToSensor::kTypeName, &roundTrip<TrackerRequestUnitToSensor>},
    {TrackerRequestWorkspace::kTypeName, &roundTrip<TrackerRequestWorkspace>},
    {ButtonChange::kTypeName, &roundTrip<ButtonChange>},
    {ButtonStates::kTypeName, &roundTrip<ButtonStates>},
    {ForcePlane::kTypeName, &roundTrip<ForcePlane>},
    {ForcePlane2::kTypeName, &roundTrip<ForcePlane2>},
    {ForceField::kTypeName, &roundTrip<ForceField>},
    {ForceCustomEffect::kTypeName, &roundTrip<ForceCustomEffect>},
    {ForceReport::kTypeName, &roundTrip<ForceReport>},
    {ForceScp::kTypeName, &roundTrip<ForceScp>},
    {ForceError::kTypeName, &roundTrip<ForceError>},
};

inline constexpr std::string_view kSenders[] = {"Tracker0", "Button0", "Phantom0"};

// Small deterministic generator for chunk sizes.
struct Chunker {
  std::uint32_t state;
  std::size_t next() {
    state ^= state << 13;
    state ^= state >> 17;
    state ^= state << 5;
    return 1 + state % ((state >> 8) % 4 == 0 ? 97 : 9);
  }
};

struct Run {
  std::vector<std::string> events;
  Failure failure;
};

inline Run runEndpoint(std::span<const std::uint8_t> stream, std::uint32_t chunk_seed) {
  Run run;
  Endpoint e(harness::fixedClock());
  for (auto s : kSenders) e.addSender(s);
  for (const auto& c : kCheckers) e.addType(c.name);
  Chunker chunker{chunk_seed | 1u};
  bool dropped = false;
  std::size_t pos = 0;
  while (pos < stream.size()) {
    const std::size_t n = chunk_seed == 0 ? stream.size() : std::min(chunker.next(), stream.size() - pos);
    e.feed(stream.subspan(pos, n));
    pos += n;
    while (auto ev = e.poll()) {
      if (dropped) {
        run.failure = "event after Dropped: " + harness::summary(*ev);
        return run;
      }
      if (std::holds_alternative<Dropped>(*ev)) dropped = true;
      if (const auto* m = std::get_if<UserMessage>(&*ev)) {
        for (const auto& c : kCheckers)
          if (c.name == m->type_name)
            if (Failure f = c.check(m->payload)) {
              run.failure = f;
              return run;
            }
      }
      run.events.push_back(harness::summary(*ev));
    }
  }
  e.finishInput();
  while (auto ev = e.poll()) run.events.push_back(harness::summary(*ev));
  return run;
}

inline std::vector<std::string> runFrames(std::span<const std::uint8_t> stream, std::uint32_t chunk_seed) {
  std::vector<std::string> out;
  FrameDecoder d;
  Chunker chunker{chunk_seed | 1u};
  std::size_t pos = 0;
  while (pos < stream.size()) {
    const std::size_t n = chunk_seed == 0 ? stream.size() : std::min(chunker.next(), stream.size() - pos);
    d.feed(stream.subspan(pos, n));
    pos += n;
    for (DecodeStep s = d.next(); !std::holds_alternative<NeedMore>(s); s = d.next()) {
      if (const auto* e = std::get_if<Error>(&s)) {
        out.push_back("error " + e->reason);
        return out;
      }
      const Frame& f = std::get<Frame>(s);
      out.push_back(std::to_string(f.header.type) + " " + harness::hexOf(f.payload));
    }
  }
  return out;
}

inline Failure fuzzDecoderOnce(std::span<const std::uint8_t> data) {
  if (data.empty()) return std::nullopt;
  const std::uint8_t mode = data[0];
  harness::Bytes stream;
  if (mode & 1) {
    const Cookie c = makeCookie();
    stream.assign(c.begin(), c.end());
  }
  stream.insert(stream.end(), data.begin() + 1, data.end());
  const std::uint32_t seed = 0x9e3779b9u * (std::uint32_t(mode >> 1) + 1);

  const Run whole = runEndpoint(stream, 0);
  if (whole.failure) return whole.failure;
  const Run chunked = runEndpoint(stream, seed);
  if (chunked.failure) return chunked.failure;
  if (whole.events != chunked.events) return std::string("endpoint events depend on chunking");

  const std::span<const std::uint8_t> frames = std::span(data).subspan(1);
  if (runFrames(frames, 0) != runFrames(frames, seed)) return std::string("frame decoder depends on chunking");

  // Every typed decoder and the addressing parsers straight on the raw bytes, too.
  for (const auto& c : kCheckers)
    if (Failure f = c.check(frames)) return f;
  if (Result<LobRequest> lob = parseLobRequest(frames)) {
    Result<LobRequest> again = parseLobRequest(encodeLobRequest(lob->host, lob->port));
    if (!again || *again != *lob) return std::string("lob request does not survive encode/parse");
  }
  (void)parseDeviceAddress(std::string_view(reinterpret_cast<const char*>(frames.data()), frames.size()));
  return std::nullopt;
}

}  // namespace thx::vrpn::fuzz
