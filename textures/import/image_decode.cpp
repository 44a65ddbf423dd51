#include "textures/import/image_decode.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

#include "textures/import/byte_fields.hpp"
#include "textures/import/image_size.hpp"
#include "textures/import/tga_decode.hpp"
#include "textures/texture_error.hpp"
#include "textures/texture_map.hpp"

namespace thx::tex {

namespace {

const char* kKnownFormats = "PNG, JPEG, BMP, TIFF, WebP, or TGA (a name ending in .tga)";

bool startsWith(const std::vector<unsigned char>& b, std::initializer_list<int> magic, std::size_t at = 0) {
  if (b.size() < at + magic.size()) return false;
  std::size_t k = at;
  for (int m : magic) {
    if (b[k++] != m) return false;
  }
  return true;
}

using bytes::le32;

bool endsWithTga(const std::string& path) {
  if (path.size() < 4) return false;
  std::string tail = path.substr(path.size() - 4);
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return tail == ".tga";
}

std::string firstBytes(const std::vector<unsigned char>& b) {
  static const char* kHex = "0123456789abcdef";
  std::string s = "first bytes";
  for (std::size_t k = 0; k < std::min<std::size_t>(b.size(), 8); ++k) {
    s += ' ';
    s += kHex[b[k] >> 4];
    s += kHex[b[k] & 15];
  }
  return s;
}

ImageFormat detect(const std::string& path, const std::vector<unsigned char>& b) {
  if (startsWith(b, {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'})) return ImageFormat::Png;
  if (startsWith(b, {0xff, 0xd8, 0xff})) return ImageFormat::Jpeg;
  if (startsWith(b, {'B', 'M'}) && b.size() >= 26) return ImageFormat::Bmp;
  if (startsWith(b, {'I', 'I', 42, 0}) || startsWith(b, {'M', 'M', 0, 42})) return ImageFormat::Tiff;
  if (startsWith(b, {'R', 'I', 'F', 'F'}) && startsWith(b, {'W', 'E', 'B', 'P'}, 8)) return ImageFormat::WebP;
  if (endsWithTga(path) && looksLikeTga(b)) return ImageFormat::Tga;
  throw TextureError(path, "unknown image format", firstBytes(b), kKnownFormats);
}

[[noreturn]] void truncated(const std::string& path, ImageFormat format, const std::string& value, const std::string& what) {
  throw TextureError(path, std::string("truncated ") + toString(format) + " file", value, what);
}

// Decoders that meet the end of a short file early may return a partly grey image with only a
// warning on stderr, so each format's own length field or end marker is checked first.
void checkComplete(const std::string& path, ImageFormat format, const std::vector<unsigned char>& b) {
  const std::string got = std::to_string(b.size()) + " bytes";
  switch (format) {
    case ImageFormat::Jpeg: {
      // The end-of-image marker FF D9 (entropy-coded data never holds it); trailing bytes after it
      // are allowed, so look near the end.
      const std::size_t from = b.size() > 65536 ? b.size() - 65536 : 2;
      for (std::size_t k = b.size() - 1; k > from; --k) {
        if (b[k - 1] == 0xff && b[k] == 0xd9) return;
      }
      truncated(path, format, got + " without the end-of-image marker (FF D9)", "a complete JPEG file");
    }
    case ImageFormat::Bmp: {
      const std::uint32_t declared = le32(b, 2);
      if (declared > b.size()) {
        truncated(path, format, got, "the " + std::to_string(declared) + " bytes its header declares");
      }
      return;
    }
    case ImageFormat::WebP: {
      const std::uint64_t declared = std::uint64_t(le32(b, 4)) + 8;
      if (declared > b.size()) {
        truncated(path, format, got, "the " + std::to_string(declared) + " bytes its RIFF header declares");
      }
      return;
    }
    default: return;  // TIFF: libtiff reports short strips itself; PNG and TGA are checked by their readers
  }
}

RawImage fromMat(const std::string& path, ImageFormat format, const cv::Mat& mat) {
  if (mat.depth() != CV_8U && mat.depth() != CV_16U) {
    throw TextureError(path, std::string("unsupported ") + toString(format) + " sample type",
                       "OpenCV depth " + std::to_string(mat.depth()) + " (floating point or signed samples)",
                       "8- or 16-bit unsigned channels");
  }
  const int channels = mat.channels();
  if (channels < 1 || channels > 4) {
    throw TextureError(path, "unsupported channel count", std::to_string(channels), "1 to 4 channels");
  }
  RawImage image;
  image.width = mat.cols;
  image.height = mat.rows;
  image.channels = channels;
  image.bit_depth = mat.depth() == CV_16U ? 16 : 8;
  image.samples.resize(std::size_t(mat.cols) * std::size_t(mat.rows) * std::size_t(channels));
  // OpenCV stores colour as BGR(A); ours is RGB(A).
  const int order[4] = {channels >= 3 ? 2 : 0, 1, channels >= 3 ? 0 : 2, 3};
  std::size_t k = 0;
  for (int y = 0; y < mat.rows; ++y) {
    for (int x = 0; x < mat.cols; ++x) {
      for (int c = 0; c < channels; ++c) {
        const int from = order[c];
        image.samples[k++] = image.bit_depth == 16 ? mat.ptr<std::uint16_t>(y)[x * channels + from]
                                                   : mat.ptr<std::uint8_t>(y)[x * channels + from];
      }
    }
  }
  return image;
}

RawImage decodeWithOpenCv(const std::string& path, ImageFormat format, const std::vector<unsigned char>& bytes) {
  // OpenCV's own pixel limit is 2^30; ours is the texture limit, read once by OpenCV.
  static const bool limited = [] {
    const std::string limit = std::to_string(std::int64_t(kMaxTextureSide) * kMaxTextureSide);
    return ::setenv("OPENCV_IO_MAX_IMAGE_PIXELS", limit.c_str(), 0) == 0;
  }();
  (void)limited;
  cv::Mat mat;
  try {
    mat = cv::imdecode(cv::Mat(1, int(bytes.size()), CV_8U, const_cast<unsigned char*>(bytes.data())),
                       cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    throw TextureError(path, std::string(toString(format)) + " decoding failed", "OpenCV: " + e.msg,
                       std::string("a valid ") + toString(format) + " file");
  }
  if (mat.empty()) {
    throw TextureError(path, std::string(toString(format)) + " decoding failed", "no image from OpenCV's decoder",
                       std::string("a valid, complete ") + toString(format) + " file");
  }
  return fromMat(path, format, mat);
}

void checkSize(const std::string& path, const RawImage& image) {
  if (image.width < kMinTextureSide || image.height < kMinTextureSide || image.width > kMaxTextureSide ||
      image.height > kMaxTextureSide) {
    throw TextureError(path, "image size out of range", std::to_string(image.width) + "x" + std::to_string(image.height),
                       "each side in [" + std::to_string(kMinTextureSide) + ", " + std::to_string(kMaxTextureSide) + "]");
  }
}

[[noreturn]] void tooLarge(const std::string& path, const HeaderSize& size, const char* whose, std::int64_t max_pixels) {
  throw TextureError(path, "image too large",
                     std::to_string(size.width) + "x" + std::to_string(size.height) + " = " +
                         std::to_string(size.pixels()) + " pixels " + whose,
                     "at most " + std::to_string(max_pixels) + " pixels");
}

}  // namespace

const char* toString(ImageFormat format) {
  switch (format) {
    case ImageFormat::Png: return "PNG";
    case ImageFormat::Jpeg: return "JPEG";
    case ImageFormat::Bmp: return "BMP";
    case ImageFormat::Tiff: return "TIFF";
    case ImageFormat::WebP: return "WebP";
    case ImageFormat::Tga: return "TGA";
  }
  return "unknown";
}

DecodedImage decodeImage(const std::string& path, const std::vector<unsigned char>& bytes, std::int64_t max_pixels) {
  if (bytes.empty()) throw TextureError(path, "empty file", "0 bytes", kKnownFormats);
  DecodedImage decoded;
  decoded.format = detect(path, bytes);
  checkComplete(path, decoded.format, bytes);
  const auto size = headerSize(decoded.format, bytes);
  // A WebP's size is bounded from its image header (the VP8, VP8L or VP8X chunk), so it must have one.
  if (!size && decoded.format == ImageFormat::WebP)
    throw TextureError(path, "corrupt WebP header", "no VP8, VP8L or VP8X image header at byte 12",
                       "a WebP file (RIFF, WEBP, then a VP8, VP8L or VP8X chunk)");
  // OpenCV picks its decoder from the bytes, not from our detection: a file its decoder refuses
  // (a WebP chunk libwebp rejects) falls through to any other decoder whose signature it holds.
  // All of them look at byte 0, where the format's own signature already is, except DICOM's
  // "DICM" at byte 128 (found by fuzzing twice: GDCM allocated gigabytes, then asserted).
  if (decoded.format != ImageFormat::Tga && startsWith(bytes, {'D', 'I', 'C', 'M'}, 128))
    throw TextureError(path, std::string("not a plain ") + toString(decoded.format) + " file",
                       "a DICOM signature (\"DICM\") at byte 128, which OpenCV would hand to its DICOM reader",
                       std::string("a ") + toString(decoded.format) + " file without \"DICM\" at byte 128");
  if (size && size->pixels() > std::uint64_t(max_pixels)) tooLarge(path, *size, "in its header", max_pixels);
  if (decoded.format == ImageFormat::Tga) {
    decoded.image = decodeTga(path, bytes);
  } else {
    decoded.image = decodeWithOpenCv(path, decoded.format, bytes);
  }
  checkSize(path, decoded.image);
  const HeaderSize decoded_size{std::uint32_t(decoded.image.width), std::uint32_t(decoded.image.height)};
  if (decoded_size.pixels() > std::uint64_t(max_pixels)) tooLarge(path, decoded_size, "decoded", max_pixels);
  return decoded;
}

DecodedImage readImage(const std::string& path, std::int64_t max_pixels) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw TextureError(path, "cannot open file", std::strerror(errno), std::string("a readable image: ") + kKnownFormats);
  const std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  if (!bytes.empty() && detect(path, bytes) == ImageFormat::Png) {
    if (const auto size = headerSize(ImageFormat::Png, bytes); size && size->pixels() > std::uint64_t(max_pixels))
      tooLarge(path, *size, "in its header", max_pixels);
    return {readPng(path), ImageFormat::Png};
  }
  return decodeImage(path, bytes, max_pixels);
}

}  // namespace thx::tex
