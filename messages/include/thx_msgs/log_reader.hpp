#pragma once
// Reading our messages back from a standard LCM log (`hapticd --record`, lcm-logger). A log is a
// file from outside, so this reader, not LCM's, parses it: LCM 1.3.1's LogFile allocates whatever
// data length an event header claims (2 GiB for a corrupt one) and silently skips bytes until the
// next sync word. Here every length is checked against its limit and the bytes left in the file
// before anything is allocated, and each event is decoded with try_decode. Used by hapticd's
// replay, the physics client's pen paths and session records, the audio and visual replays.
//
//   thx_msgs::forEachLogMessage<thx_msgs::device_state_t>(path, "THX_DEVICE_STATE",
//       [&](const thx_msgs::device_state_t& m, const thx_msgs::LogPosition& at) { ... });
//
// Errors throw LogError, whose message names the file, the event and the expected type or field:
//   session.lcm: event 12 (THX_DEVICE_STATE): does not decode as device_state_t
//   session.lcm: event 3 at byte 4120: data length 2147483647 exceeds the 16777216-byte limit
//
// Event layout (LCM's, big-endian): sync word 0xEDA1DA01, int64 event number, int64 timestamp
// (us), int32 channel length, int32 data length, the channel's bytes, the data. A last event cut
// short (a recorder killed mid-write) ends the log, as with LCM's reader; truncatedAt() says where.
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "thx_msgs/protocol.hpp"

namespace thx_msgs {

inline constexpr std::uint32_t kLogSyncWord = 0xEDA1DA01u;
inline constexpr std::size_t kLogEventHeaderBytes = 4 + 8 + 8 + 4 + 4;
// The longest event data the reader accepts. Our largest messages are below 64 KiB (a contact
// batch fits one udpm datagram, docs/messages.md); LCM itself fragments up to 256 MiB, so this
// leaves room for other types in a shared log while keeping a corrupt length from asking for GiBs.
inline constexpr std::int64_t kMaxLogEventDataBytes = std::int64_t{16} << 20;

struct LogPosition {
  std::string file;
  long event = 0;  // 1-based index among all events of the file
  std::string channel;
  std::int64_t timestamp_us = 0;
  // "FILE: event N (CHANNEL)", the prefix of every error about this event.
  std::string where() const { return file + ": event " + std::to_string(event) + " (" + channel + ")"; }
};

class LogError : public thx::Error {
 public:
  explicit LogError(const std::string& what) : thx::Error(Kind::Io, what) {}
};

// One event as stored.
struct LogRecord {
  std::int64_t eventnum = 0;
  std::int64_t timestamp_us = 0;
  std::string channel;
  std::vector<std::uint8_t> data;
  std::int64_t offset = 0;  // byte offset of its sync word in the file
};

class LogReader {
 public:
  // Opens `path`; throws LogError naming it when it cannot be opened or sized.
  explicit LogReader(const std::string& path) : name_(path) {
    file_ = std::fopen(path.c_str(), "rb");
    if (!file_) throw LogError(path + ": cannot open as an LCM log file: " + std::strerror(errno));
    owned_ = true;
    measure();
  }
  // Reads from an open stream (not closed here); `name` stands for it in messages.
  LogReader(std::FILE* stream, std::string name) : name_(std::move(name)), file_(stream) {
    if (!file_) throw LogError(name_ + ": no stream to read the LCM log from");
    measure();
  }
  ~LogReader() {
    if (owned_) std::fclose(file_);
  }
  LogReader(const LogReader&) = delete;
  LogReader& operator=(const LogReader&) = delete;

  const std::string& name() const { return name_; }
  // Events read so far (the 1-based index of the last one).
  long events() const { return events_; }
  // Byte offset of the next event (the end of the last whole one).
  std::int64_t offset() const { return pos_; }
  // Where a cut-short last event began, or -1.
  std::int64_t truncatedAt() const { return truncated_at_; }

  // Reads the next event into `out`. Returns false at the end of the log (or at a last event cut
  // short). Throws LogError naming the file, the event's index and byte offset, and the field
  // that is wrong: the sync word, the channel length (1..kMaxChannelLength), the data length
  // (0..kMaxLogEventDataBytes), or a read error.
  bool next(LogRecord& out) {
    if (pos_ >= size_ || truncated_at_ >= 0) return false;
    const std::int64_t left = size_ - pos_;
    if (left < std::int64_t(kLogEventHeaderBytes)) return cutShort();
    std::uint8_t h[kLogEventHeaderBytes];
    readExactly(h, sizeof h);
    const std::uint32_t sync = detail::read_be32(h);
    const std::int64_t eventnum = std::int64_t(be64(h + 4));
    const std::int64_t timestamp = std::int64_t(be64(h + 12));
    const std::int64_t channel_len = std::int32_t(detail::read_be32(h + 20));
    const std::int64_t data_len = std::int32_t(detail::read_be32(h + 24));
    const std::string at = name_ + ": event " + std::to_string(events_ + 1) + " at byte " + std::to_string(pos_);
    if (sync != kLogSyncWord) throw LogError(at + ": sync word " + hex32(sync) + ", expected " + hex32(kLogSyncWord) + " (not an LCM log, or corrupt)");
    if (channel_len < 1 || channel_len > std::int64_t(kMaxChannelLength))
      throw LogError(at + ": channel length " + std::to_string(channel_len) + ", expected 1.." +
                     std::to_string(kMaxChannelLength));
    if (data_len < 0 || data_len > kMaxLogEventDataBytes)
      throw LogError(at + ": data length " + std::to_string(data_len) + ", expected 0.." +
                     std::to_string(kMaxLogEventDataBytes));
    if (channel_len + data_len > left - std::int64_t(kLogEventHeaderBytes)) return cutShort();
    out.eventnum = eventnum;
    out.timestamp_us = timestamp;
    out.offset = pos_;
    out.channel.resize(std::size_t(channel_len));
    readExactly(out.channel.data(), out.channel.size());
    out.data.resize(std::size_t(data_len));
    readExactly(out.data.data(), out.data.size());
    pos_ += std::int64_t(kLogEventHeaderBytes) + channel_len + data_len;
    ++events_;
    return true;
  }

 private:
  static std::uint64_t be64(const std::uint8_t* p) {
    return (std::uint64_t{detail::read_be32(p)} << 32) | detail::read_be32(p + 4);
  }
  static std::string hex32(std::uint32_t v) {
    char b[16];
    std::snprintf(b, sizeof b, "0x%08X", v);
    return b;
  }
  void measure() {
    if (std::fseek(file_, 0, SEEK_END) != 0) throw LogError(name_ + ": cannot seek in the LCM log file");
    size_ = std::ftell(file_);
    if (size_ < 0 || std::fseek(file_, 0, SEEK_SET) != 0) throw LogError(name_ + ": cannot size the LCM log file");
  }
  void readExactly(void* dst, std::size_t n) {
    if (n > 0 && std::fread(dst, 1, n, file_) != n)
      throw LogError(name_ + ": read error at byte " + std::to_string(pos_) + " (file changed while read?)");
  }
  bool cutShort() {
    truncated_at_ = pos_;
    return false;
  }

  std::string name_;
  std::FILE* file_ = nullptr;
  bool owned_ = false;
  std::int64_t size_ = 0;
  std::int64_t pos_ = 0;
  std::int64_t truncated_at_ = -1;
  long events_ = 0;
};

// Decodes a record as M; throws LogError naming the event and the type when it does not decode.
// A record whose fingerprint (its first 8 bytes) is not this build's M says so: a log recorded by
// a build with another layout of M (another protocol version, docs/messages.md §2) is not corrupt,
// only to be recorded again.
template <class M>
void decodeLogRecord(const LogRecord& r, const LogPosition& at, M& out) {
  if (try_decode(r.data.data(), r.data.size(), out) >= 0) return;
  std::uint64_t hash = 0;
  if (r.data.size() >= 8) {
    for (int i = 0; i < 8; ++i) hash = (hash << 8) | static_cast<std::uint8_t>(r.data[std::size_t(i)]);
  }
  if (r.data.size() >= 8 && hash != static_cast<std::uint64_t>(M::getHash()))
    throw LogError(at.where() + ": does not decode as " + M::getTypeName() +
                   " (wrong type, or recorded by a build with another layout of it: another protocol version; "
                   "record it again with this build)");
  throw LogError(at.where() + ": does not decode as " + M::getTypeName() + " (wrong type or corrupt)");
}

// Calls fn(message, position) for every event on `channel`, in file order. Throws LogError when
// the log is malformed or an event on the channel does not decode as M; what fn throws passes
// through.
template <class M, class Fn>
void forEachLogMessage(LogReader& log, const std::string& channel, Fn fn) {
  LogRecord r;
  while (log.next(r)) {
    if (r.channel != channel) continue;
    const LogPosition at{log.name(), log.events(), r.channel, r.timestamp_us};
    M m;
    decodeLogRecord(r, at, m);
    fn(static_cast<const M&>(m), at);
  }
}

template <class M, class Fn>
void forEachLogMessage(const std::string& path, const std::string& channel, Fn fn) {
  LogReader log(path);
  forEachLogMessage<M>(log, channel, fn);
}

}  // namespace thx_msgs
