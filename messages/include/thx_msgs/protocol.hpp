#pragma once
// Conventions that go with the thx_msgs LCM types (docs/messages.md): channel names, stream
// names, client-id rules, and a decode that is safe on untrusted bytes.
//
// Header-only. Depends on the lcm-gen output (target thx_messages) and the standard library.
#include <climits>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

#include "thx_msgs/client_force_t.hpp"
#include "thx_msgs/contact_batch_t.hpp"
#include "thx_msgs/contact_t.hpp"
#include "thx_msgs/device_state_t.hpp"
#include "thx_msgs/heartbeat_t.hpp"
#include "thx_msgs/hello_t.hpp"
#include "thx_msgs/physics_contacts_t.hpp"
#include "thx_msgs/physics_impact_t.hpp"
#include "thx_msgs/physics_poses_t.hpp"
#include "thx_msgs/physics_texel_t.hpp"
#include "thx_msgs/server_command_reply_t.hpp"
#include "thx_msgs/server_command_t.hpp"
#include "thx_msgs/servo_stats_t.hpp"
#include "thx_msgs/subscribe_reply_t.hpp"
#include "thx_msgs/subscribe_request_t.hpp"

// The default LCM URL of every program (server, clients, tools): UDP multicast on this host only
// (ttl=0). A macro as well, so help texts can quote it as a literal.
#define THX_DEFAULT_LCM_URL "udpm://239.255.76.67:7667?ttl=0"

namespace thx_msgs {

inline constexpr char kDefaultLcmUrl[] = THX_DEFAULT_LCM_URL;

// ---- Fixed channels -------------------------------------------------------------------------
inline constexpr char kChannelHello[] = "THX_HELLO";                     // hello_t, server -> all
inline constexpr char kChannelSubscribe[] = "THX_SUBSCRIBE";             // subscribe_request_t
inline constexpr char kChannelSubscribeReply[] = "THX_SUBSCRIBE_REPLY";  // subscribe_reply_t
inline constexpr char kChannelHeartbeat[] = "THX_HEARTBEAT";             // heartbeat_t
inline constexpr char kChannelClientForce[] = "THX_CLIENT_FORCE";        // client_force_t
inline constexpr char kChannelCommand[] = "THX_COMMAND";                 // server_command_t
inline constexpr char kChannelCommandReply[] = "THX_COMMAND_REPLY";      // server_command_reply_t
// Published by physics-client for the audio and visual clients (docs/messages.md §9). Poses and
// impacts are fixed-size; physics_contacts_t has one variable array (its texel path): decode it
// with try_decode, which checks the count first.
inline constexpr char kChannelPhysicsPoses[] = "THX_PHYSICS_POSES";        // physics_poses_t
inline constexpr char kChannelPhysicsImpact[] = "THX_PHYSICS_IMPACT";      // physics_impact_t
inline constexpr char kChannelPhysicsContacts[] = "THX_PHYSICS_CONTACTS";  // physics_contacts_t

// ---- Streams (subscribe_request_t.stream) -----------------------------------------------------
inline constexpr std::string_view kStreamDeviceState = "DEVICE_STATE";  // device_state_t
inline constexpr std::string_view kStreamContact = "CONTACT";           // contact_t, or contact_batch_t
inline constexpr std::string_view kStreamServoStats = "SERVO_STATS";    // servo_stats_t
// The channel prefix of a batched CONTACT subscription (contact_batch_t).
inline constexpr std::string_view kStreamContactBatch = "CONTACT_BATCH";

inline constexpr std::string_view kChannelPrefix = "THX_";

// The same three streams as a type, for code: the client kit's subscribe() takes a Stream, so a
// misspelt stream does not compile. The wire carries stream_name(); parse_stream() reads a name a
// user typed (probe-client --stream), and kStreamNames lists the valid ones for its error.
enum class Stream { DeviceState, Contact, ServoStats };
inline constexpr Stream kStreams[] = {Stream::DeviceState, Stream::Contact, Stream::ServoStats};
inline constexpr char kStreamNames[] = "DEVICE_STATE, CONTACT or SERVO_STATS";

// "DEVICE_STATE", "CONTACT", "SERVO_STATS" (the kStream* above, NUL-terminated); "" for a value
// outside the enum (only a cast makes one).
constexpr const char* stream_name(Stream s) noexcept {
  switch (s) {
    case Stream::DeviceState: return kStreamDeviceState.data();
    case Stream::Contact: return kStreamContact.data();
    case Stream::ServoStats: return kStreamServoStats.data();
  }
  return "";
}

// The stream `name` names, exactly as on the wire (case matters); nullopt for anything else.
constexpr std::optional<Stream> parse_stream(std::string_view name) noexcept {
  for (Stream s : kStreams) {
    if (name == stream_name(s)) return s;
  }
  return std::nullopt;
}

// ---- Strings --------------------------------------------------------------------------------
// client_id and source tags end up in channel names and logs: short, plain ASCII.
inline constexpr std::size_t kMaxClientIdLength = 32;
inline constexpr std::size_t kMaxTagLength = 32;
// Any other string a peer sends (reason, server_name, device) should stay below this.
inline constexpr std::size_t kMaxTextLength = 200;
// LCM 1.3.1 rejects longer channel names (LCM_MAX_CHANNEL_NAME_LENGTH in lcm/lcm.h).
inline constexpr std::size_t kMaxChannelLength = 63;
// LCM 1.3.1 udpm sends (channel name + 1 + encoded message) in one datagram up to this many
// bytes and fragments anything larger; losing one fragment loses the whole message.
inline constexpr std::size_t kLcmShortMessageMaxSize = 65499;

namespace detail {
inline bool is_id_char(char c, bool allow_dot) noexcept {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-' || (allow_dot && c == '.');
}
}  // namespace detail

// 1..32 characters of [A-Za-z0-9_-].
inline bool is_valid_client_id(std::string_view id) noexcept {
  if (id.empty() || id.size() > kMaxClientIdLength) return false;
  for (char c : id) {
    if (!detail::is_id_char(c, false)) return false;
  }
  return true;
}

// client_force_t.source: 1..32 characters of [A-Za-z0-9_.-].
inline bool is_valid_source_tag(std::string_view tag) noexcept {
  if (tag.empty() || tag.size() > kMaxTagLength) return false;
  for (char c : tag) {
    if (!detail::is_id_char(c, true)) return false;
  }
  return true;
}

inline bool is_known_stream(std::string_view stream) noexcept {
  return stream == kStreamDeviceState || stream == kStreamContact || stream == kStreamServoStats;
}

// Only CONTACT has a batched form (contact_batch_t).
inline bool stream_supports_batch(std::string_view stream) noexcept { return stream == kStreamContact; }
constexpr bool stream_supports_batch(Stream stream) noexcept { return stream == Stream::Contact; }

// The per-client channel a subscription is published on: "THX_<STREAM>.<client_id>", with
// STREAM = CONTACT_BATCH for a batched CONTACT subscription. The server sends this string in
// subscribe_reply_t.channel; clients listen on what the reply says. Returns "" when the stream
// is unknown, batching is asked of a stream without it, or the client id is invalid.
inline std::string stream_channel(std::string_view stream, bool batch, std::string_view client_id) {
  if (!is_known_stream(stream) || (batch && !stream_supports_batch(stream)) || !is_valid_client_id(client_id)) {
    return {};
  }
  std::string ch(kChannelPrefix);
  ch += batch ? kStreamContactBatch : stream;
  ch += '.';
  ch += client_id;
  return ch;
}
inline std::string stream_channel(Stream stream, bool batch, std::string_view client_id) {
  return stream_channel(std::string_view(stream_name(stream)), batch, client_id);
}

// ---- Decoding untrusted bytes ---------------------------------------------------------------
// The lcm-gen 1.3.1 decoders return < 0 on a short buffer or a wrong fingerprint, but corrupt
// input can also make them
//  - THROW: a string length of 0 or below -> std::string::assign(p, size_t(len - 1)) throws
//    std::length_error;
//  - READ OUT OF BOUNDS: a string length of INT32_MIN -> len - 1 wraps to INT32_MAX and assign
//    copies 2 GiB from the buffer (SIGSEGV);
//  - ALLOCATE ~700 GB: a corrupt batch count -> std::vector::resize(count) before any check.
// LCM's typed subscribe() runs decode() inside a C callback where nothing can be caught. For
// anything a peer sends (every client -> server channel), use an untyped subscribe() and
// try_decode(), which checks string lengths and counts before the generated decoder runs.

namespace detail {
inline std::uint32_t read_be32(const std::uint8_t* p) noexcept {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | std::uint32_t{p[3]};
}

// A type's encoding after its 8-byte fingerprint, as runs of fixed-size bytes (> 0) and
// strings (kString). Must follow the field order of messages/<type>.lcm; tests/messages checks
// every layout against the generated encoder.
inline constexpr int kString = -1;
template <class T>
struct string_layout {
  static constexpr bool has_strings = false;
};
template <>
struct string_layout<subscribe_request_t> {
  static constexpr bool has_strings = true;
  // utime seq | client_id | stream | action rate_hz batch
  static constexpr int segments[] = {16, kString, kString, 13};
};
template <>
struct string_layout<subscribe_reply_t> {
  static constexpr bool has_strings = true;
  // utime server_instance request_seq | client_id | stream | action accepted | reason |
  // rate_hz batch | channel | heartbeat_timeout_us | data_url
  static constexpr int segments[] = {24, kString, kString, 5, kString, 9, kString, 8, kString};
};
template <>
struct string_layout<heartbeat_t> {
  static constexpr bool has_strings = true;
  // utime seq server_instance | client_id
  static constexpr int segments[] = {24, kString};
};
template <>
struct string_layout<hello_t> {
  static constexpr bool has_strings = true;
  // utime seq server_instance start_utime start_unix_us protocol_version servo_rate_hz |
  // server_name | device | scene_name | texture_fingerprint | control_url | device_names
  static constexpr int segments[] = {52, kString, kString, kString, 8, kString, kString};
};
template <>
struct string_layout<server_command_t> {
  static constexpr bool has_strings = true;
  // utime seq | client_id | action | argument
  static constexpr int segments[] = {16, kString, 4, kString};
};
template <>
struct string_layout<server_command_reply_t> {
  static constexpr bool has_strings = true;
  // utime server_instance request_seq | client_id | action accepted | reason | tick
  static constexpr int segments[] = {24, kString, 5, kString, 8};
};
template <>
struct string_layout<client_force_t> {
  static constexpr bool has_strings = true;
  // utime seq ref_tick timeout_us | client_id | source | f_world tau_world p_world device
  static constexpr int segments[] = {32, kString, kString, 76};
};

// Walks an encoded message by its layout. Returns the number of bytes it spans (fingerprint
// included), or -1 when the buffer is too short or a string length is outside [1, bytes left]
// or the string lacks its terminating NUL or holds another NUL before it.
template <std::size_t N>
std::ptrdiff_t layout_extent(const void* data, std::size_t size, const int (&segments)[N]) noexcept {
  const auto* b = static_cast<const std::uint8_t*>(data);
  std::size_t pos = 8;
  if (size < pos) return -1;
  for (int seg : segments) {
    if (seg != kString) {
      if (size - pos < static_cast<std::size_t>(seg)) return -1;
      pos += static_cast<std::size_t>(seg);
      continue;
    }
    if (size - pos < 4) return -1;
    const std::uint32_t u = read_be32(b + pos);
    pos += 4;
    if (u == 0 || u > 0x7fffffffu || u > size - pos) return -1;  // also rejects negative int32
    if (b[pos + u - 1] != 0) return -1;
    // An embedded NUL would survive decode (std::string keeps it) but not encode (strlen), so the
    // message would change on its way through: refused (found by tests/fuzz, docs/fuzzing.md).
    if (std::memchr(b + pos, 0, u - 1) != nullptr) return -1;
    pos += u;
  }
  return static_cast<std::ptrdiff_t>(pos);
}
}  // namespace detail

// Encoded size of one contact_t inside a batch (no fingerprint). Fixed.
inline int contact_sample_encoded_size() noexcept { return contact_t{}._getEncodedSizeNoHash(); }

// Byte offset of contact_batch_t.num_samples in an encoded batch: the fingerprint (8), four
// int64 fields, device and num_dropped (tests/messages check this against the generated encoder).
inline constexpr std::size_t kBatchCountOffset = 8 + 4 * 8 + 4 + 4;
// Encoded size of a batch with no samples (fingerprint included).
inline constexpr std::size_t kBatchHeaderBytes = kBatchCountOffset + 4;

// Encoded size of a batch of n samples.
inline std::size_t contact_batch_encoded_size(std::size_t n) noexcept {
  return kBatchHeaderBytes + n * static_cast<std::size_t>(contact_sample_encoded_size());
}
// The most samples a batch may carry and still go out over udpm as one datagram on a channel
// of `channel_length` characters (165 for every valid channel name, 166 up to 46 characters).
inline std::size_t max_unfragmented_batch_samples(std::size_t channel_length = kMaxChannelLength) noexcept {
  const std::size_t overhead = channel_length + 1 + kBatchHeaderBytes;
  if (overhead >= kLcmShortMessageMaxSize) return 0;
  return (kLcmShortMessageMaxSize - overhead) / static_cast<std::size_t>(contact_sample_encoded_size());
}

// physics_contacts_t ends in its variable texel path: the count `num_path` sits just before it, at
// a fixed offset (every field before it is fixed-size), and each texel is a fixed-size
// physics_texel_t. Both are read from the generated code, not counted by hand.
inline std::size_t physics_path_count_offset() noexcept {
  return static_cast<std::size_t>(physics_contacts_t{}.getEncodedSize()) - 4;
}
inline std::size_t physics_texel_encoded_size() noexcept {
  return static_cast<std::size_t>(physics_texel_t{}._getEncodedSizeNoHash());
}
// Encoded size of a physics_contacts_t whose path holds n texels (fingerprint included).
inline std::size_t physics_contacts_encoded_size(std::size_t n) noexcept {
  return physics_path_count_offset() + 4 + n * physics_texel_encoded_size();
}

namespace detail {
// A variable array's count checked against the bytes after it before decode() resizes a vector.
inline bool count_fits(const void* data, std::size_t size, std::size_t count_offset, std::size_t element_size) noexcept {
  if (size < count_offset + 4) return false;
  const std::uint32_t count = read_be32(static_cast<const std::uint8_t*>(data) + count_offset);
  if (count > 0x7fffffffu) return false;  // negative int32
  return count <= (size - count_offset - 4) / element_size;
}
}  // namespace detail

// Decodes `size` bytes at `data` into `out`. Returns the number of bytes decoded (> 0), or -1
// on a short or corrupt buffer or a wrong fingerprint. Never throws, never reads outside
// [data, data + size), never allocates more than the buffer can describe. `out` is unspecified
// on -1.
template <class T>
int try_decode(const void* data, std::size_t size, T& out) noexcept {
  if (data == nullptr || size > static_cast<std::size_t>(INT_MAX)) return -1;
  if constexpr (detail::string_layout<T>::has_strings) {
    if (detail::layout_extent(data, size, detail::string_layout<T>::segments) < 0) return -1;
  }
  if constexpr (std::is_same_v<T, contact_batch_t>) {
    // Check the sample count against the bytes present before decode() resizes the vector.
    if (!detail::count_fits(data, size, kBatchCountOffset, static_cast<std::size_t>(contact_sample_encoded_size()))) return -1;
  }
  if constexpr (std::is_same_v<T, physics_contacts_t>) {
    if (!detail::count_fits(data, size, physics_path_count_offset(), physics_texel_encoded_size())) return -1;
  }
  try {
    const int n = out.decode(data, 0, static_cast<int>(size));
    return n < 0 ? -1 : n;
  } catch (...) {
    return -1;
  }
}

// The generated encoder trusts num_samples: it must equal samples.size() before encode()/
// getEncodedSize()/publish(), or they read past the vector.
inline bool batch_count_consistent(const contact_batch_t& b) noexcept {
  return b.num_samples >= 0 && static_cast<std::size_t>(b.num_samples) == b.samples.size();
}
// The same rule for physics_contacts_t's texel path.
inline bool path_count_consistent(const physics_contacts_t& m) noexcept {
  return m.num_path >= 0 && static_cast<std::size_t>(m.num_path) == m.path.size();
}

}  // namespace thx_msgs
