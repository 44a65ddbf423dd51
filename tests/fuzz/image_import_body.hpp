#pragma once
// One fuzzing step for the import of other image formats (textures/import/): format detection,
// the length checks, OpenCV's codecs (JPEG, BMP, TIFF, WebP, PNG) and stb_image (TGA), then the
// normal-map import. Shared by the libFuzzer target and the short run in test_fuzz_image_import.cpp.
//
// Input: byte 0 picks the mode (bit 0: the file is named fuzz.tga, so a TGA header is read as
// TGA; bits 1-2: alpha ignored, height or depth; bit 3: DirectX green), the rest is the file.
// Images are decoded with the importer's own maximum pixel count (`texturetool import
// --max-pixels`) at kFuzzMaxPixels, 256 x 256: a few bytes of header may declare up to 16384^2
// pixels, and decoding, importing and saving a large image cost milliseconds to seconds per input
// (page faults and clearing, mostly) and no more code; the seeds are 8 x 8. OpenCV's own pixel
// limit is lowered to the same value for the process (OPENCV_IO_MAX_IMAGE_PIXELS, set before the
// first decode; the importer keeps a value already set), for a header our check cannot read.
// Properties:
//  1. a refused file raises TextureError naming the file;
//  2. an accepted image is consistent (each side in [2, 16384], 1-4 channels, 8 or 16 bits,
//     samples matching, each within the bit depth), of at most kFuzzMaxPixels pixels; a TGA has
//     the size its header gives;
//  3. the import refuses with a TextureError naming the file, or gives a map of the image's size
//     whose warnings name the file and whose saved form (encodeTexture) loads again with the
//     Reject policy to the same size, representation and depth codes.
#include <cstdint>
#include <cstdlib>
#include <span>

#include <opencv2/core/utils/logger.hpp>
#include <string>

#include "tests/fuzz/raw_image_checks.hpp"
#include "tests/fuzz/failure.hpp"
#include "textures/import/image_decode.hpp"
#include "textures/import/normal_import.hpp"
#include "textures/texture_error.hpp"
#include "textures/texture_io.hpp"

namespace thx::fuzz {

inline constexpr long kFuzzMaxPixels = 1 << 16;

namespace import_detail {

inline Failure checkDecoded(const tex::DecodedImage& d, std::span<const std::uint8_t> file) {
  const tex::RawImage& img = d.image;
  if (Failure f = checkRawImage(img)) return f;
  if (std::int64_t(img.width) * img.height > kFuzzMaxPixels) return std::string("accepted more pixels than the maximum");
  if (d.format == tex::ImageFormat::Tga &&
      (img.width != (file[12] | file[13] << 8) || img.height != (file[14] | file[15] << 8)))
    return std::string("TGA decoded to another size than its header's");
  return std::nullopt;
}

inline Failure checkImported(const tex::TextureMap& map, const tex::RawImage& img, const tex::ImportReport& report,
                             const std::string& source, tex::GreenConvention green) {
  if (map.width() != img.width || map.height() != img.height) return std::string("imported map of another size");
  for (const std::string& w : report.warnings)
    if (Failure f = mustName(w, source, "import warning")) return f;
  tex::SaveOptions save;
  save.green = green;
  tex::LoadOptions load;
  load.green = green;
  tex::TextureMap back;
  try {
    back = tex::decodeTexture(tex::encodeTexture(map, source, save), source, load);
  } catch (const tex::TextureError& e) {
    return std::string("an imported map does not load again once saved: ") + e.what();
  }
  if (back.width() != map.width() || back.height() != map.height() || back.representation() != map.representation())
    return std::string("saved import changed size or representation");
  if (map.isRelief())
    for (int j = 0; j < map.height(); ++j)
      for (int i = 0; i < map.width(); ++i)
        if (back.depthCode(i, j) != map.depthCode(i, j)) return std::string("saved import changed a depth");
  return std::nullopt;
}

}  // namespace import_detail

inline Failure fuzzImageImportOnce(std::span<const std::uint8_t> data) {
  static const bool limited = [] {
    // OpenCV logs a warning per refused file; its imdecode still prints refused headers to stderr.
    cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
    return ::setenv("OPENCV_IO_MAX_IMAGE_PIXELS", std::to_string(kFuzzMaxPixels).c_str(), 1) == 0;
  }();
  (void)limited;
  if (data.empty()) return std::nullopt;
  const std::uint8_t mode = data[0];
  const std::span<const std::uint8_t> file = data.subspan(1);
  const std::string source = (mode & 1) ? "fuzz.tga" : "fuzz.img";
  tex::DecodedImage decoded;
  try {
    decoded = tex::decodeImage(source, std::vector<unsigned char>(file.begin(), file.end()), kFuzzMaxPixels);
  } catch (const tex::TextureError& e) {
    if (e.source() != source) return "TextureError with source '" + e.source() + "'";
    return mustName(e.what(), source, "image refusal");
  }
  if (Failure f = import_detail::checkDecoded(decoded, file)) return f;

  tex::ImportOptions options;
  options.green = (mode & 8) ? tex::GreenConvention::DirectX : tex::GreenConvention::OpenGL;
  const int alpha = (mode >> 1) & 3;
  options.alpha = alpha == 1 ? tex::AlphaMeaning::Height : alpha == 2 ? tex::AlphaMeaning::Depth : tex::AlphaMeaning::None;
  if (options.alpha != tex::AlphaMeaning::None) options.alpha_scale_m = 0.002;
  tex::ImportReport report;
  tex::TextureMap map;
  try {
    map = tex::importNormalMap(decoded, source, options, &report);
  } catch (const tex::TextureError& e) {
    if (e.source() != source) return "TextureError with source '" + e.source() + "'";
    return mustName(e.what(), source, "import refusal");
  }
  return import_detail::checkImported(map, decoded.image, report, source, options.green);
}

}  // namespace thx::fuzz
