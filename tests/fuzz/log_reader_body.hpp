#pragma once
// One fuzzing step for the LCM log reader (thx_msgs::LogReader, forEachLogMessage: hapticd
// --replay / --device replay:, the physics client's pen paths and session records, audio-client and
// visual-client --replay-log), shared by the libFuzzer target (libfuzzer/log_reader.cpp) and the
// short run in `make test` (test_fuzz_log_reader.cpp). The input is the whole log file, read
// through fmemopen() so the reader's own stdio path runs. Returns the first broken property.
//
// Properties:
//  1. the reader stops with LogError or at the end; its message names the file, the event's index
//     and byte offset (the offset it stopped at) and the field; no other exception escapes;
//  2. the events it returned, written back in LCM's event layout, are exactly the input's bytes
//     up to where it stopped (read . write = identity), and it stops at the end of the input
//     unless it threw or met a cut-short last event (then truncatedAt() is that offset);
//  3. each event on one of our channels that try_decode accepts re-encodes to the bytes it
//     consumed (lcm_round_trip.hpp); forEachLogMessage's errors name the file, event and type.
// Allocation is bounded by construction (lengths checked against the bytes left); ASan's and
// libFuzzer's malloc limits would report a violation.
#include <cstdint>
#include <cstdio>
#include <optional>
#include <span>
#include <string>
#include <thx_msgs/log_reader.hpp>
#include <vector>

#include "tests/fuzz/lcm_round_trip.hpp"

namespace thx::fuzz::log_reader {

using Failure = std::optional<std::string>;
using Bytes = std::vector<std::uint8_t>;

inline constexpr char kName[] = "fuzz.lcm";

inline void putBe(Bytes& out, std::uint64_t v, int bytes) {
  for (int k = bytes - 1; k >= 0; --k) out.push_back(std::uint8_t(v >> (8 * k)));
}

// One event in LCM's log layout (the writer side of property 2).
inline void appendEvent(Bytes& out, const thx_msgs::LogRecord& r) {
  putBe(out, thx_msgs::kLogSyncWord, 4);
  putBe(out, std::uint64_t(r.eventnum), 8);
  putBe(out, std::uint64_t(r.timestamp_us), 8);
  putBe(out, r.channel.size(), 4);
  putBe(out, r.data.size(), 4);
  out.insert(out.end(), r.channel.begin(), r.channel.end());
  out.insert(out.end(), r.data.begin(), r.data.end());
}

inline Failure decodeByChannel(const thx_msgs::LogRecord& r) {
  using namespace thx_msgs;
  using lcm_round_trip::roundTrip;
  const std::span<const std::uint8_t> d(r.data);
  const std::string& c = r.channel;
  if (c == "THX_DEVICE_STATE") return roundTrip<device_state_t>(d);
  if (c == "THX_CONTACT") return roundTrip<contact_t>(d);
  if (c == kChannelHello) return roundTrip<hello_t>(d);
  if (c == kChannelPhysicsPoses) return roundTrip<physics_poses_t>(d);
  if (c == kChannelPhysicsImpact) return roundTrip<physics_impact_t>(d);
  if (c == kChannelPhysicsContacts) return roundTrip<physics_contacts_t>(d);
  if (c == kChannelSubscribe) return roundTrip<subscribe_request_t>(d);
  if (c == kChannelClientForce) return roundTrip<client_force_t>(d);
  return std::nullopt;
}

// An fmemopen stream over the (non-empty: fmemopen refuses size 0) input.
struct MemFile {
  std::FILE* f = nullptr;
  explicit MemFile(std::span<const std::uint8_t> data)
      : f(fmemopen(const_cast<std::uint8_t*>(data.data()), data.size(), "rb")) {}
  ~MemFile() {
    if (f) std::fclose(f);
  }
  MemFile(const MemFile&) = delete;
  MemFile& operator=(const MemFile&) = delete;
};

inline Failure fuzzOnce(std::span<const std::uint8_t> data) {
  if (data.empty()) return std::nullopt;  // fmemopen needs a byte; the empty file has a unit test
  MemFile mem(data);
  if (!mem.f) return std::string("fmemopen failed");
  Bytes rewritten;
  bool threw = false;
  std::int64_t stopped = 0;
  {
    thx_msgs::LogReader reader(mem.f, kName);
    thx_msgs::LogRecord r;
    try {
      while (reader.next(r)) {
        if (r.offset != std::int64_t(rewritten.size())) return std::string("event offset does not follow the last event");
        appendEvent(rewritten, r);
        if (Failure f = decodeByChannel(r)) return f;
      }
    } catch (const thx_msgs::LogError& e) {
      threw = true;
      const std::string want = std::string(kName) + ": event " + std::to_string(reader.events() + 1) + " at byte " +
                               std::to_string(reader.offset()) + ": ";
      const std::string what = e.what();
      if (what.rfind(want, 0) != 0) return "LogError does not start with '" + want + "': " + what;
      if (what.find("sync word") == std::string::npos && what.find("channel length") == std::string::npos &&
          what.find("data length") == std::string::npos)
        return "LogError names no field: " + what;
    } catch (const std::exception& e) {
      return std::string("unexpected exception from the log reader: ") + e.what();
    }
    stopped = reader.offset();
    if (!threw && reader.truncatedAt() < 0 && stopped != std::int64_t(data.size()))
      return "the reader stopped at byte " + std::to_string(stopped) + " of " + std::to_string(data.size()) +
             " without an error or a cut-short event";
    if (reader.truncatedAt() >= 0 && reader.truncatedAt() != stopped)
      return std::string("truncatedAt() is not where the reader stopped");
  }
  if (rewritten.size() != std::size_t(stopped) || !std::equal(rewritten.begin(), rewritten.end(), data.begin()))
    return "the events read, written back, are not the input's first " + std::to_string(stopped) + " bytes";

  // forEachLogMessage as hapticd's replay uses it: errors name file, event and type.
  MemFile again(data);
  try {
    thx_msgs::LogReader reader(again.f, kName);
    thx_msgs::forEachLogMessage<thx_msgs::device_state_t>(reader, "THX_DEVICE_STATE",
                                                          [](const thx_msgs::device_state_t&, const thx_msgs::LogPosition&) {});
  } catch (const thx_msgs::LogError& e) {
    const std::string what = e.what();
    if (what.rfind(std::string(kName) + ": event ", 0) != 0) return "forEachLogMessage error names no event: " + what;
    if (what.find("(THX_DEVICE_STATE): does not decode as device_state_t") == std::string::npos &&
        what.find(" at byte ") == std::string::npos)
      return "forEachLogMessage error names neither type nor byte: " + what;
  } catch (const std::exception& e) {
    return std::string("unexpected exception from forEachLogMessage: ") + e.what();
  }
  return std::nullopt;
}

}  // namespace thx::fuzz::log_reader
