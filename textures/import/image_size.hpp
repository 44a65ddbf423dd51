#pragma once
// The pixel size a file's header declares, read before any decoder allocates the image: so that a
// maximum pixel count (ImportOptions::max_pixels, `texturetool import --max-pixels`) refuses a
// large image from its first bytes rather than after decoding it.
#include <cstdint>
#include <optional>
#include <vector>

#include "textures/import/image_decode.hpp"

namespace thx::tex {

struct HeaderSize {
  std::uint32_t width = 0, height = 0;
  // Exact: both sides are below 2^32, so the product fits 64 bits.
  std::uint64_t pixels() const { return std::uint64_t(width) * height; }
};

// Width and height from the header of `format` (PNG IHDR, the first JPEG frame header, BMP's info
// header, the first TIFF directory, WebP's VP8/VP8L/VP8X header, TGA's header); nothing when the
// header is too short or malformed to say (the decoder then refuses it, or the size of what it
// decoded is checked instead).
std::optional<HeaderSize> headerSize(ImageFormat format, const std::vector<unsigned char>& bytes);

}  // namespace thx::tex
