#include "textures/import/image_size.hpp"

#include <cstdlib>

#include "textures/import/byte_fields.hpp"

namespace thx::tex {

namespace {

using bytes::Bytes;
using bytes::be16;
using bytes::be32;
using bytes::le16;
using bytes::le32;

bool has(const Bytes& b, std::size_t at, std::size_t n) { return at <= b.size() && n <= b.size() - at; }

std::optional<HeaderSize> png(const Bytes& b) {
  if (!has(b, 16, 8)) return std::nullopt;
  return HeaderSize{be32(b, 16), be32(b, 20)};
}

// Markers from the start of image to the first frame header (SOF0..SOF15 but DHT C4, JPG C8 and
// DAC CC, which share the range): its height and width.
std::optional<HeaderSize> jpeg(const Bytes& b) {
  std::size_t at = 2;
  while (has(b, at, 4)) {
    if (b[at] != 0xff) return std::nullopt;
    const unsigned marker = b[at + 1];
    if (marker == 0xff) {  // fill byte
      ++at;
      continue;
    }
    if (marker == 0xd8 || marker == 0x01 || (marker >= 0xd0 && marker <= 0xd7)) {  // no length
      at += 2;
      continue;
    }
    const std::size_t length = be16(b, at + 2);
    if (marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc) {
      if (length < 7 || !has(b, at + 4, 5)) return std::nullopt;
      return HeaderSize{be16(b, at + 7), be16(b, at + 5)};
    }
    if (marker == 0xda || marker == 0xd9 || length < 2) return std::nullopt;  // scan or end before a frame
    at += 2 + length;
  }
  return std::nullopt;
}

std::optional<HeaderSize> bmp(const Bytes& b) {
  if (!has(b, 14, 4)) return std::nullopt;
  const std::uint32_t info = le32(b, 14);
  if (info == 12) {  // BITMAPCOREHEADER: 16-bit sides
    if (!has(b, 18, 4)) return std::nullopt;
    return HeaderSize{le16(b, 18), le16(b, 20)};
  }
  if (!has(b, 18, 8)) return std::nullopt;
  // Signed: a negative height is a top-down image of that many rows.
  const auto side = [&](std::size_t at) { return std::uint32_t(std::llabs(std::int32_t(le32(b, at)))); };
  return HeaderSize{side(18), side(22)};
}

// The first image file directory's ImageWidth (256) and ImageLength (257), SHORT or LONG.
std::optional<HeaderSize> tiff(const Bytes& b) {
  if (!has(b, 0, 8)) return std::nullopt;
  const bool big = b[0] == 'M';
  const auto u16 = [&](std::size_t at) { return big ? be16(b, at) : le16(b, at); };
  const auto u32 = [&](std::size_t at) { return big ? be32(b, at) : le32(b, at); };
  const std::size_t ifd = u32(4);
  if (!has(b, ifd, 2)) return std::nullopt;
  const std::size_t entries = u16(ifd);
  std::optional<std::uint32_t> width, height;
  for (std::size_t k = 0; k < entries; ++k) {
    const std::size_t e = ifd + 2 + 12 * k;
    if (!has(b, e, 12)) return std::nullopt;
    const std::uint32_t tag = u16(e), type = u16(e + 2);
    if (tag != 256 && tag != 257) continue;
    if (type != 3 && type != 4) return std::nullopt;
    (tag == 256 ? width : height) = type == 3 ? u16(e + 8) : u32(e + 8);
  }
  if (!width || !height) return std::nullopt;
  return HeaderSize{*width, *height};
}

std::optional<HeaderSize> webp(const Bytes& b) {
  if (!has(b, 12, 4)) return std::nullopt;
  const bool vp8 = b[12] == 'V' && b[13] == 'P' && b[14] == '8';
  if (!vp8) return std::nullopt;
  if (b[15] == ' ') {  // lossy: a key frame's start code, then 14-bit sides
    if (!has(b, 23, 7) || b[23] != 0x9d || b[24] != 0x01 || b[25] != 0x2a) return std::nullopt;
    return HeaderSize{le16(b, 26) & 0x3fff, le16(b, 28) & 0x3fff};
  }
  if (b[15] == 'L') {  // lossless: signature 0x2f, then 14 bits each of width - 1 and height - 1
    if (!has(b, 20, 5) || b[20] != 0x2f) return std::nullopt;
    const std::uint32_t bits = le32(b, 21);
    return HeaderSize{(bits & 0x3fff) + 1, ((bits >> 14) & 0x3fff) + 1};
  }
  if (b[15] == 'X') {  // extended: 24-bit canvas width - 1 and height - 1
    if (!has(b, 24, 7)) return std::nullopt;
    return HeaderSize{(le32(b, 24) & 0xffffff) + 1, (le32(b, 27) & 0xffffff) + 1};
  }
  return std::nullopt;
}

std::optional<HeaderSize> tga(const Bytes& b) {
  if (!has(b, 12, 4)) return std::nullopt;
  return HeaderSize{le16(b, 12), le16(b, 14)};
}

}  // namespace

std::optional<HeaderSize> headerSize(ImageFormat format, const std::vector<unsigned char>& bytes) {
  switch (format) {
    case ImageFormat::Png: return png(bytes);
    case ImageFormat::Jpeg: return jpeg(bytes);
    case ImageFormat::Bmp: return bmp(bytes);
    case ImageFormat::Tiff: return tiff(bytes);
    case ImageFormat::WebP: return webp(bytes);
    case ImageFormat::Tga: return tga(bytes);
  }
  return std::nullopt;
}

}  // namespace thx::tex
