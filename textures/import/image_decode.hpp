#pragma once
// Reading the image files people have: PNG (libpng, as everywhere), JPEG, BMP, TIFF and WebP
// (OpenCV's codecs) and TGA (stb_image, Debian's libstb). Only the offline tools link this:
// hapticd reads PNG alone and never loads OpenCV (docs/textures.md, "Importing").
//
// The format is told from the file's first bytes; TGA has no signature, so a file that matches
// none and whose name ends in .tga is read as TGA. Errors are TextureError naming the file: not
// readable, empty, an unknown format, truncated (checked from each format's own length fields
// or end marker, since some decoders fill a short file with grey instead of failing), a decoder
// failure, a sample type other than 8 or 16 bits, a size outside [2, 16384] per side, more pixels
// than `max_pixels` (checked from the header before decoding where the header says, and on the
// decoded image in any case; `texturetool import --max-pixels`), a WebP without an image header
// (OpenCV chooses its decoder from the bytes, and would pass it to another one).
#include <cstdint>
#include <string>
#include <vector>

#include "textures/png_io.hpp"
#include "textures/texture_map.hpp"

namespace thx::tex {

enum class ImageFormat { Png, Jpeg, Bmp, Tiff, WebP, Tga };
const char* toString(ImageFormat format);

struct DecodedImage {
  RawImage image;  // RGB(A) channel order, row 0 = top
  ImageFormat format = ImageFormat::Png;
};

// The default maximum pixel count: the texture limit, 16384 x 16384.
inline constexpr std::int64_t kMaxImagePixels = std::int64_t(kMaxTextureSide) * kMaxTextureSide;

DecodedImage readImage(const std::string& path, std::int64_t max_pixels = kMaxImagePixels);
// The same from bytes already read; `path` names them in errors and decides .tga.
DecodedImage decodeImage(const std::string& path, const std::vector<unsigned char>& bytes,
                         std::int64_t max_pixels = kMaxImagePixels);

}  // namespace thx::tex
