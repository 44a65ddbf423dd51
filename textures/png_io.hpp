#pragma once
// Minimal PNG reading and writing on libpng (no OpenCV codecs: the real-time server links this).
// Errors are TextureError naming the file: unreadable, not a PNG, truncated or corrupt data,
// unsupported layout, size outside [kMinTextureSide, kMaxTextureSide] (checked from the header,
// before any pixel memory is allocated).
#include <cstdint>
#include <map>
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

// Palette images are expanded to RGB(A); 1/2/4-bit grayscale to 8 bit.
RawImage readPng(const std::string& path);
void writePng(const std::string& path, const RawImage& image);

}  // namespace thx::tex
