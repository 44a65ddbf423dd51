#include "textures/png_io.hpp"

#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>

#include "textures/texture_error.hpp"
#include "textures/texture_map.hpp"

namespace thx::tex {

namespace {

// libpng reports errors by longjmp. Everything with a destructor lives outside the function
// that calls setjmp (in ReadState/WriteState, reached through a pointer), so the jump never
// skips a C++ destructor.
struct ErrorSink {
  char message[256] = {0};
};

void onPngError(png_structp png, png_const_charp msg) {
  auto* sink = static_cast<ErrorSink*>(png_get_error_ptr(png));
  std::snprintf(sink->message, sizeof sink->message, "%s", msg ? msg : "unknown libpng error");
  png_longjmp(png, 1);
}
void onPngWarning(png_structp, png_const_charp) {}  // benign chunk warnings (iCCP, sRGB) are not our concern

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

enum class ReadStatus { Ok, LibpngError, TooSmall, TooLarge, UnsupportedLayout };

struct ReadState {
  RawImage image;
  std::vector<png_byte> bytes;
  std::vector<png_bytep> rows;
  std::vector<std::pair<std::string, std::string>> text;
  ErrorSink sink;
  png_uint_32 width = 0, height = 0;
  int color_type = 0;
};

void collectText(png_structp png, png_infop info, ReadState& st) {
  png_textp text = nullptr;
  int count = 0;
  if (png_get_text(png, info, &text, &count) > 0) {
    for (int k = 0; k < count; ++k) {
      st.text.emplace_back(text[k].key ? text[k].key : "", text[k].text ? std::string(text[k].text, text[k].text_length ? text[k].text_length : std::strlen(text[k].text)) : "");
    }
  }
}

ReadStatus readInto(std::FILE* fp, ReadState* st) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &st->sink, onPngError, onPngWarning);
  if (!png) return ReadStatus::LibpngError;
  png_infop info = png_create_info_struct(png);
  png_infop end_info = png_create_info_struct(png);
  if (!info || !end_info) {
    png_destroy_read_struct(&png, &info, &end_info);
    return ReadStatus::LibpngError;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, &end_info);
    return ReadStatus::LibpngError;
  }
  png_init_io(png, fp);
  png_set_sig_bytes(png, 8);
  png_set_user_limits(png, 0x7fffffff, 0x7fffffff);  // our own limit is checked below, with a better message
  png_read_info(png, info);

  st->width = png_get_image_width(png, info);
  st->height = png_get_image_height(png, info);
  if (st->width < png_uint_32(kMinTextureSide) || st->height < png_uint_32(kMinTextureSide)) {
    png_destroy_read_struct(&png, &info, &end_info);
    return ReadStatus::TooSmall;
  }
  if (st->width > png_uint_32(kMaxTextureSide) || st->height > png_uint_32(kMaxTextureSide)) {
    png_destroy_read_struct(&png, &info, &end_info);
    return ReadStatus::TooLarge;
  }
  st->color_type = png_get_color_type(png, info);
  const int bit_depth = png_get_bit_depth(png, info);
  if (st->color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (st->color_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (bit_depth == 16) png_set_swap(png);  // PNG is big-endian; we want native uint16
  png_set_interlace_handling(png);
  png_read_update_info(png, info);

  const int channels = png_get_channels(png, info);
  const int out_depth = png_get_bit_depth(png, info);
  if (channels < 1 || channels > 4 || (out_depth != 8 && out_depth != 16)) {
    png_destroy_read_struct(&png, &info, &end_info);
    return ReadStatus::UnsupportedLayout;
  }
  const std::size_t rowbytes = png_get_rowbytes(png, info);
  st->bytes.resize(rowbytes * st->height);
  st->rows.resize(st->height);
  for (png_uint_32 y = 0; y < st->height; ++y) st->rows[y] = st->bytes.data() + rowbytes * y;
  png_read_image(png, st->rows.data());
  png_read_end(png, end_info);
  collectText(png, info, *st);
  collectText(png, end_info, *st);

  st->image.width = int(st->width);
  st->image.height = int(st->height);
  st->image.channels = channels;
  st->image.bit_depth = out_depth;
  png_destroy_read_struct(&png, &info, &end_info);
  return ReadStatus::Ok;
}

struct WriteState {
  std::vector<png_byte> bytes;
  std::vector<png_bytep> rows;
  std::vector<std::string> keys, values;
  std::vector<png_text> text;
  ErrorSink sink;
};

bool writeFrom(std::FILE* fp, const RawImage& img, WriteState* st) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &st->sink, onPngError, onPngWarning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, fp);
  static const int kColorTypes[5] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                     PNG_COLOR_TYPE_RGB_ALPHA};
  png_set_IHDR(png, info, png_uint_32(img.width), png_uint_32(img.height), img.bit_depth, kColorTypes[img.channels],
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (!st->text.empty()) png_set_text(png, info, st->text.data(), int(st->text.size()));
  png_write_info(png, info);
  if (img.bit_depth == 16) png_set_swap(png);
  png_write_image(png, st->rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

RawImage readPng(const std::string& path) {
  FilePtr fp(std::fopen(path.c_str(), "rb"));
  if (!fp) throw TextureError(path, "cannot open file", std::strerror(errno), "a readable PNG file");
  png_byte signature[8] = {0};
  const std::size_t got = std::fread(signature, 1, 8, fp.get());
  if (got < 8) {
    throw TextureError(path, "not a PNG file", "only " + std::to_string(got) + " bytes",
                       "at least the 8-byte PNG signature");
  }
  if (png_sig_cmp(signature, 0, 8) != 0) {
    throw TextureError(path, "not a PNG file", "wrong signature",
                       "a PNG file (convert JPG, TGA, BMP, TIFF or WebP with texturetool import)");
  }

  auto st = std::make_unique<ReadState>();
  const ReadStatus status = readInto(fp.get(), st.get());
  const std::string size = std::to_string(st->width) + "x" + std::to_string(st->height);
  switch (status) {
    case ReadStatus::Ok:
      break;
    case ReadStatus::LibpngError:
      throw TextureError(path, "truncated or corrupt PNG data", std::string("libpng: ") + st->sink.message,
                         "a complete, valid PNG file");
    case ReadStatus::TooSmall:
      throw TextureError(path, "image too small", size,
                         "at least " + std::to_string(kMinTextureSide) + "x" + std::to_string(kMinTextureSide));
    case ReadStatus::TooLarge:
      throw TextureError(path, "image too large", size,
                         "at most " + std::to_string(kMaxTextureSide) + "x" + std::to_string(kMaxTextureSide));
    case ReadStatus::UnsupportedLayout:
      throw TextureError(path, "unsupported PNG layout", "color type " + std::to_string(st->color_type),
                         "gray, gray+alpha, RGB or RGBA with 8 or 16 bits per channel");
  }

  RawImage& img = st->image;
  const std::size_t n = std::size_t(img.width) * std::size_t(img.height) * std::size_t(img.channels);
  img.samples.resize(n);
  if (img.bit_depth == 8) {
    for (std::size_t k = 0; k < n; ++k) img.samples[k] = st->bytes[k];
  } else {
    std::memcpy(img.samples.data(), st->bytes.data(), n * sizeof(std::uint16_t));
  }
  for (auto& [key, value] : st->text) img.text[key] = value;
  return std::move(img);
}

void writePng(const std::string& path, const RawImage& img) {
  if (img.channels < 1 || img.channels > 4 || (img.bit_depth != 8 && img.bit_depth != 16) || img.width < 1 ||
      img.height < 1 ||
      img.samples.size() != std::size_t(img.width) * std::size_t(img.height) * std::size_t(img.channels)) {
    throw TextureError(path, "cannot write an inconsistent image",
                       std::to_string(img.width) + "x" + std::to_string(img.height) + "x" +
                           std::to_string(img.channels) + " @" + std::to_string(img.bit_depth) + " bit",
                       "1-4 channels, 8 or 16 bit, samples matching the size");
  }
  auto st = std::make_unique<WriteState>();
  const std::size_t bytes_per_sample = img.bit_depth == 16 ? 2 : 1;
  const std::size_t rowbytes = std::size_t(img.width) * std::size_t(img.channels) * bytes_per_sample;
  st->bytes.resize(rowbytes * std::size_t(img.height));
  if (img.bit_depth == 8) {
    for (std::size_t k = 0; k < img.samples.size(); ++k) st->bytes[k] = png_byte(img.samples[k] & 0xff);
  } else {
    std::memcpy(st->bytes.data(), img.samples.data(), img.samples.size() * sizeof(std::uint16_t));
  }
  st->rows.resize(std::size_t(img.height));
  for (int y = 0; y < img.height; ++y) st->rows[std::size_t(y)] = st->bytes.data() + rowbytes * std::size_t(y);
  for (const auto& [key, value] : img.text) {
    st->keys.push_back(key);
    st->values.push_back(value);
  }
  st->text.resize(st->keys.size());
  for (std::size_t k = 0; k < st->keys.size(); ++k) {
    st->text[k] = png_text{};
    st->text[k].compression = PNG_TEXT_COMPRESSION_NONE;
    st->text[k].key = st->keys[k].data();
    st->text[k].text = st->values[k].data();
    st->text[k].text_length = st->values[k].size();
  }

  FilePtr fp(std::fopen(path.c_str(), "wb"));
  if (!fp) throw TextureError(path, "cannot create file", std::strerror(errno), "a writable path");
  if (!writeFrom(fp.get(), img, st.get())) {
    throw TextureError(path, "PNG encoding failed", std::string("libpng: ") + st->sink.message, "a writable image");
  }
  if (std::fflush(fp.get()) != 0) throw TextureError(path, "write failed", std::strerror(errno), "enough disk space");
}

}  // namespace thx::tex
