// The LCM log reader (thx_msgs::LogReader) under the short fixed-seed fuzz run
// (tests/fuzz/short_run.hpp, body in log_reader_body.hpp), checked against LCM's own reader on
// well-formed logs, and its length caps.
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>

#include <fstream>

#include "tests/fuzz/log_reader_body.hpp"
#include "tests/fuzz/seed_writer.hpp"
#include "tests/fuzz/short_run.hpp"
#include "tests/messages/message_fixtures.hpp"
#include "tests/support/temp_dir.hpp"

namespace thx::fuzz::test_fuzz_log_reader {
namespace {

using namespace thx_msgs;

struct Event {
  std::string channel;
  Bytes data;
  std::int64_t timestamp = 0;
};

template <class T>
Event event(const std::string& channel, const T& m, std::int64_t t) {
  return {channel, lcm_round_trip::encoded(m), t};
}

// Writes `events` with LCM's own writer (as hapticd --record does) and returns the file's bytes.
Bytes lcmLog(const std::string& path, const std::vector<Event>& events) {
  {
    lcm::LogFile log(path, "w");
    for (const Event& e : events) {
      lcm::LogEvent le{};
      le.timestamp = e.timestamp;
      le.channel = e.channel;
      le.datalen = std::int32_t(e.data.size());
      le.data = const_cast<std::uint8_t*>(e.data.data());
      EXPECT_EQ(log.writeEvent(&le), 0);
    }
  }
  std::ifstream f(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

// A session as hapticd records it (hello, device states, contacts) with the physics client's
// streams, and a log holding one corrupt device state.
std::vector<std::pair<std::string, Bytes>> seeds(const test::TempDir& dir) {
  std::vector<Event> session = {event(kChannelHello, thx_test::make_hello(1), 10),
                                event("THX_DEVICE_STATE", thx_test::make_device_state(1), 11),
                                event("THX_CONTACT", thx_test::make_contact(1), 11),
                                event("THX_DEVICE_STATE", thx_test::make_device_state(2), 12),
                                event("THX_CONTACT", thx_test::make_contact(2), 12)};
  physics_contacts_t pc{};
  pc.num_path = 2;
  pc.path.resize(2);
  physics_poses_t poses{};
  physics_impact_t impact{};
  std::vector<Event> physics = session;
  physics.push_back(event(kChannelPhysicsPoses, poses, 13));
  physics.push_back(event(kChannelPhysicsImpact, impact, 13));
  physics.push_back(event(kChannelPhysicsContacts, pc, 14));
  std::vector<Event> corrupt = {event("THX_DEVICE_STATE", thx_test::make_device_state(3), 1)};
  corrupt.push_back({"THX_DEVICE_STATE", Bytes{1, 2, 3, 4, 5, 6, 7, 8, 9}, 2});
  return {{"session.lcm", lcmLog(dir.file("s.lcm"), session)},
          {"session_physics.lcm", lcmLog(dir.file("p.lcm"), physics)},
          {"corrupt_device_state.lcm", lcmLog(dir.file("c.lcm"), corrupt)}};
}

// The events LCM's reader returns for a file, and ours (`whole`: read to its end without an error).
std::vector<Event> lcmEvents(const std::string& path) {
  lcm::LogFile log(path, "r");
  std::vector<Event> out;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    const auto* p = static_cast<const std::uint8_t*>(e->data);
    out.push_back({e->channel, Bytes(p, p + e->datalen), e->timestamp});
  }
  return out;
}
std::vector<Event> ourEvents(const std::string& path, bool& whole) {
  std::vector<Event> out;
  whole = false;
  try {
    LogReader r(path);
    for (LogRecord rec; r.next(rec);) out.push_back({rec.channel, rec.data, rec.timestamp_us});
    whole = r.truncatedAt() < 0;
  } catch (const LogError&) {
  }
  return out;
}
bool same(const std::vector<Event>& a, const std::vector<Event>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].channel != b[i].channel || a[i].data != b[i].data || a[i].timestamp != b[i].timestamp) return false;
  return true;
}

TEST(FuzzLogReader, WriteSeedCorpusWhenAsked) {
  test::TempDir dir("thx_fuzz");
  writeSeedsWhenAsked(seeds(dir));
}

TEST(FuzzLogReader, CheckedInSeedsAreTheGeneratedOnes) {
  test::TempDir dir("thx_fuzz");
  const std::vector<Bytes> corpus = loadCorpus("log_reader");
  for (const auto& [name, bytes] : seeds(dir))
    EXPECT_NE(std::find(corpus.begin(), corpus.end(), bytes), corpus.end()) << name << " missing from the corpus";
}

// Differential check: where our reader reads a whole file without an error or a cut-short tail,
// LCM's reader returns the same events (seeds and a fixed sample of mutated inputs). Elsewhere they
// differ on purpose: LCM skips garbage to the next sync word, allocates lengths we refuse, and
// drops an event that is followed by a partial header ("Invalid header after log data").
TEST(FuzzLogReader, AgreesWithLcmOnWhatItAccepts) {
  test::TempDir dir("thx_fuzz");
  const std::vector<Bytes> pool = loadCorpus("log_reader");
  const std::vector<Bytes> dict = loadDictionary("log_reader");
  Rng rng;
  int compared = 0;
  for (int i = 0; i < 400; ++i) {
    Bytes input = pool[std::size_t(i) % pool.size()];
    if (i >= int(pool.size())) mutate(input, rng, pool, dict);
    const std::string path = dir.file("in.lcm");
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(input.data()), std::streamsize(input.size()));
    bool whole = false;
    const std::vector<Event> ours = ourEvents(path, whole);
    if (!whole) continue;  // (and LCM would allocate the lengths we refuse)
    ++compared;
    EXPECT_TRUE(same(ours, lcmEvents(path))) << "input: " << hexOf(input);
  }
  EXPECT_GT(compared, 40);
}

// The caps: a data length above kMaxLogEventDataBytes is refused before anything is allocated,
// naming the field; one within the cap but beyond the file ends the log as a cut-short event.
TEST(FuzzLogReader, LengthsAreBoundedBeforeAllocation) {
  auto header = [](std::uint32_t channel_len, std::uint32_t data_len) {
    Bytes b;
    log_reader::putBe(b, kLogSyncWord, 4);
    log_reader::putBe(b, 0, 8);
    log_reader::putBe(b, 5, 8);
    log_reader::putBe(b, channel_len, 4);
    log_reader::putBe(b, data_len, 4);
    b.insert(b.end(), {'T', 'H', 'X', '_', 'A'});
    return b;
  };
  auto read = [](const Bytes& b) {
    log_reader::MemFile mem(b);
    LogReader r(mem.f, "cap.lcm");
    LogRecord rec;
    try {
      EXPECT_FALSE(r.next(rec));
      return std::to_string(r.truncatedAt());
    } catch (const LogError& e) {
      return std::string(e.what());
    }
  };
  EXPECT_EQ(read(header(5, std::uint32_t(kMaxLogEventDataBytes) + 1)),
            "cap.lcm: event 1 at byte 0: data length 16777217, expected 0..16777216");
  EXPECT_EQ(read(header(5, 0x7fffffff)), "cap.lcm: event 1 at byte 0: data length 2147483647, expected 0..16777216");
  EXPECT_EQ(read(header(5, 0xffffffff)), "cap.lcm: event 1 at byte 0: data length -1, expected 0..16777216");
  EXPECT_EQ(read(header(64, 0)), "cap.lcm: event 1 at byte 0: channel length 64, expected 1..63");
  EXPECT_EQ(read(header(0x80000000, 0)), "cap.lcm: event 1 at byte 0: channel length -2147483648, expected 1..63");
  EXPECT_EQ(read(header(5, std::uint32_t(kMaxLogEventDataBytes))), "0");  // cut short at byte 0
  Bytes bad = header(5, 0);
  bad[0] = 0;
  EXPECT_EQ(read(bad), "cap.lcm: event 1 at byte 0: sync word 0x00A1DA01, expected 0xEDA1DA01 (not an LCM log, or corrupt)");
}

TEST(FuzzLogReader, AnEmptyFileIsAnEmptyLog) {
  test::TempDir dir("thx_fuzz");
  std::ofstream(dir.file("empty.lcm")).close();
  LogReader r(dir.file("empty.lcm"));
  LogRecord rec;
  EXPECT_FALSE(r.next(rec));
  EXPECT_EQ(r.truncatedAt(), -1);
}

TEST(FuzzLogReader, ShortRun) { shortRun("log_reader", &log_reader::fuzzOnce); }

}  // namespace
}  // namespace thx::fuzz::test_fuzz_log_reader
