#pragma once
// What every accepted image must be, whichever decoder read it (png_texture_body.hpp,
// image_import_body.hpp): within the texture size limits, 1-4 channels of 8 or 16 bits, one sample
// per channel and pixel, each within the bit depth.
#include <string>

#include "tests/fuzz/failure.hpp"
#include "textures/png_io.hpp"
#include "textures/texture_map.hpp"

namespace thx::fuzz {

inline Failure checkRawImage(const tex::RawImage& img) {
  if (img.width < tex::kMinTextureSide || img.height < tex::kMinTextureSide || img.width > tex::kMaxTextureSide ||
      img.height > tex::kMaxTextureSide)
    return "accepted an image of " + std::to_string(img.width) + "x" + std::to_string(img.height);
  if (img.channels < 1 || img.channels > 4 || (img.bit_depth != 8 && img.bit_depth != 16))
    return std::string("accepted an unsupported layout");
  if (img.samples.size() != std::size_t(img.width) * std::size_t(img.height) * std::size_t(img.channels))
    return std::string("sample count does not match the size");
  for (std::uint16_t v : img.samples)
    if (v > img.maxValue()) return std::string("a sample exceeds the bit depth");
  return std::nullopt;
}

}  // namespace thx::fuzz
