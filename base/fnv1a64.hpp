#pragma once
// FNV-1a 64 (offset basis 0xcbf29ce484222325, prime 0x100000001b3) over a byte stream written
// host-independently: integers little-endian whatever the host, geometry quantised to 1e-12 so
// that a last-bit difference of a computed value (libm on another host) does not change it. The
// fingerprints that hello_t carries are built with it (textures/texture_fingerprint.hpp,
// scenes/scene_mesh.hpp).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace thx {

class Fnv1a64 {
 public:
  void byte(std::uint8_t b) {
    h_ ^= b;
    h_ *= 0x100000001b3ULL;
  }
  template <class UInt>
  void le(UInt v) {  // little-endian, whatever the host
    for (std::size_t k = 0; k < sizeof(UInt); ++k) byte(std::uint8_t(v >> (8 * k)));
  }
  void i16(std::int16_t v) { le(std::uint16_t(v)); }
  void i32(std::int32_t v) { le(std::uint32_t(v)); }
  // Geometry in units of 1e-12 (picometres for lengths); non-finite values hash as INT64_MIN.
  void quantised(double v) {
    const double scaled = v * 1e12;
    le(std::uint64_t(std::isfinite(scaled) && std::fabs(scaled) < 9e18 ? std::llround(scaled) : INT64_MIN));
  }
  // A definition's name, NUL-padded to 16 bytes: a new definition gets a new tag.
  void tag(const char* name) {
    char t[16] = {};
    std::memcpy(t, name, std::min<std::size_t>(std::strlen(name), sizeof t));
    for (char c : t) byte(std::uint8_t(c));
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

}  // namespace thx
