#pragma once
// Unsigned fields of an image file's header, read from a byte buffer at an offset the caller has
// bounds-checked: big-endian (PNG, JPEG) and little-endian (BMP, WebP, TGA).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace thx::tex::bytes {

using Bytes = std::vector<unsigned char>;

inline std::uint32_t be16(const Bytes& b, std::size_t at) { return std::uint32_t(b[at]) << 8 | b[at + 1]; }
inline std::uint32_t le16(const Bytes& b, std::size_t at) { return b[at] | std::uint32_t(b[at + 1]) << 8; }
inline std::uint32_t be32(const Bytes& b, std::size_t at) { return be16(b, at) << 16 | be16(b, at + 2); }
inline std::uint32_t le32(const Bytes& b, std::size_t at) { return le16(b, at) | le16(b, at + 2) << 16; }

}  // namespace thx::tex::bytes
