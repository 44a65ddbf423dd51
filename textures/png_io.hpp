#pragma once
// Minimal PNG reading and writing on libpng (no OpenCV codecs: the real-time server links this).
// Errors are TextureError naming the file: unreadable, not a PNG, truncated or corrupt data,
// unsupported layout, size outside [kMinTextureSide, kMaxTextureSide] (checked from the header,
// before any pixel memory is allocated), or more pixel data than the file's bytes can hold at
// zlib's largest compression ratio (1032:1; so pixel memory stays within ~1032x the file size).
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace thx::tex {

struct RawImage {
  int width = 0;
  int height = 0;
  int channels = 0;   // 1 gray, 2 gray+alpha, 3 RGB, 4 RGBA
  int bit_depth = 8;  // 8 or 16
  std::vector<std::uint16_t> samples;  // row-major, row 0 = top, interleaved channels
  std::map<std::string, std::string> text;  // tEXt/iTXt chunks

  std::uint16_t at(int x, int y, int c) const {
    return samples[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * std::size_t(channels) + std::size_t(c)];
  }
  int maxValue() const { return bit_depth == 16 ? 65535 : 255; }
};

// Palette images are expanded to RGB(A); 1/2/4-bit grayscale to 8 bit. A chunk stating more bytes
// than follow it is refused before libpng sees it (libpng allocates a text chunk's stated length
// before reading it). Writing refuses a text key
// that is not a PNG keyword (1-79 printable Latin-1 characters, no leading/trailing/double space).
RawImage readPng(const std::string& path);
void writePng(const std::string& path, const RawImage& image);
// The same in memory; `source` names the bytes in errors.
RawImage decodePng(std::span<const std::uint8_t> bytes, const std::string& source);
std::vector<std::uint8_t> encodePng(const RawImage& image, const std::string& source);

}  // namespace thx::tex
