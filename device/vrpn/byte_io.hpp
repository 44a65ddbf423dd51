#pragma once
// Big-endian reading and writing of the VRPN wire types (docs/vrpn.md §4): integers in network
// order, float32 sent as its bit pattern like a uint32, float64 byte-reversed as a whole (i.e. the
// 8-byte big-endian bit pattern).
//
// ByteWriter appends to a caller-owned vector (the caller reuses it, so steady-state encoding does
// not allocate). ByteReader never reads out of bounds: a read past the end returns 0 and latches
// ok() == false; decoders check the exact size first and use ok() as a second line of defence.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace thx::vrpn {

class ByteWriter {
 public:
  explicit ByteWriter(std::vector<std::uint8_t>& out) : out_(out) {}

  void u32(std::uint32_t v) {
    out_.push_back(std::uint8_t(v >> 24));
    out_.push_back(std::uint8_t(v >> 16));
    out_.push_back(std::uint8_t(v >> 8));
    out_.push_back(std::uint8_t(v));
  }
  void i32(std::int32_t v) { u32(std::bit_cast<std::uint32_t>(v)); }
  void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
  void f64(double v) {
    const auto bits = std::bit_cast<std::uint64_t>(v);
    u32(std::uint32_t(bits >> 32));
    u32(std::uint32_t(bits));
  }
  void bytes(std::span<const std::uint8_t> b) { out_.insert(out_.end(), b.begin(), b.end()); }
  void chars(std::string_view s) { out_.insert(out_.end(), s.begin(), s.end()); }
  void zeros(std::size_t n) { out_.insert(out_.end(), n, std::uint8_t{0}); }
  std::size_t size() const { return out_.size(); }

 private:
  std::vector<std::uint8_t>& out_;
};

class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> in) : in_(in) {}

  std::uint32_t u32() {
    if (remaining() < 4) return fail();
    const std::uint8_t* p = in_.data() + pos_;
    pos_ += 4;
    return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) | std::uint32_t(p[3]);
  }
  std::int32_t i32() { return std::bit_cast<std::int32_t>(u32()); }
  float f32() { return std::bit_cast<float>(u32()); }
  double f64() {
    const std::uint64_t hi = u32();
    const std::uint64_t lo = u32();
    return std::bit_cast<double>((hi << 32) | lo);
  }
  // The next n bytes (empty and !ok() if fewer remain).
  std::span<const std::uint8_t> bytes(std::size_t n) {
    if (remaining() < n) {
      fail();
      return {};
    }
    auto s = in_.subspan(pos_, n);
    pos_ += n;
    return s;
  }
  void skip(std::size_t n) { bytes(n); }
  std::size_t remaining() const { return in_.size() - pos_; }
  bool ok() const { return ok_; }

 private:
  std::uint32_t fail() {
    ok_ = false;
    pos_ = in_.size();
    return 0;
  }

  std::span<const std::uint8_t> in_;
  std::size_t pos_ = 0;
  bool ok_ = true;
};

}  // namespace thx::vrpn
