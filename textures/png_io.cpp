#include "textures/png_io.hpp"

#include <png.h>

#include <cctype>
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

enum class ReadStatus { Ok, LibpngError, TooSmall, TooLarge, UnsupportedLayout, ShortData };

// The bytes of a PNG in memory, read by libpng through onRead.
struct Cursor {
  const png_byte* data = nullptr;
  std::size_t size = 0, at = 0;
};

void onRead(png_structp png, png_bytep out, png_size_t n) {
  auto* c = static_cast<Cursor*>(png_get_io_ptr(png));
  if (n > c->size - c->at) png_error(png, "unexpected end of data");
  std::memcpy(out, c->data + c->at, n);
  c->at += n;
}

// deflate codes at most 258 bytes in one bit pair (a length and a distance code of at least one
// bit each), so no zlib stream expands more than 1032 times. Pixel memory for a size that the
// file's bytes cannot hold would be allocated for nothing: such a file is refused first.
constexpr std::uint64_t kMaxInflateRatio = 1032;
constexpr std::uint64_t kInflateSlackBytes = 1 << 16;

// libpng allocates (and clears) a text chunk's stated length before reading it, so a few bytes
// stating 2 GB would cost 2 GB: every chunk must fit in the bytes that follow it. Returns the
// problem, or "" if every chunk up to IEND (or the end of the bytes) fits.
std::string chunkThatOverruns(std::span<const std::uint8_t> b) {
  std::size_t at = 8;
  while (b.size() - at >= 8) {
    const std::uint32_t length = std::uint32_t(b[at]) << 24 | std::uint32_t(b[at + 1]) << 16 |
                                 std::uint32_t(b[at + 2]) << 8 | std::uint32_t(b[at + 3]);
    std::string type;
    for (std::size_t k = 4; k < 8; ++k) {
      char c[8];
      std::snprintf(c, sizeof c, std::isalpha(b[at + k]) ? "%c" : "\\x%02x", b[at + k]);
      type += c;
    }
    const std::size_t left = b.size() - at - 8;
    if (std::uint64_t(length) + 4 > left)
      return "chunk '" + type + "' at byte " + std::to_string(at) + " states " + std::to_string(length) +
             " bytes of data but " + std::to_string(left < 4 ? 0 : left - 4) + " follow";
    at += 12 + length;
    if (type == "IEND") break;
  }
  return "";
}

struct ReadState {
  RawImage image;
  std::vector<png_byte> bytes;
  std::vector<png_bytep> rows;
  std::vector<std::pair<std::string, std::string>> text;
  ErrorSink sink;
  png_uint_32 width = 0, height = 0;
  int color_type = 0;
  std::uint64_t needed_bytes = 0;  // of decompressed image data, for ShortData
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

ReadStatus readInto(Cursor* in, ReadState* st) {
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
  png_set_read_fn(png, in, onRead);
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
  // Before the transforms below expand it: what the compressed stream must hold.
  const std::size_t stored_rowbytes = png_get_rowbytes(png, info);
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
  // Filter bytes and Adam7's passes add a little to this; the bound below is loose.
  st->needed_bytes = std::uint64_t(stored_rowbytes) * st->height;
  if (st->needed_bytes > kMaxInflateRatio * (in->size - in->at) + kInflateSlackBytes) {
    png_destroy_read_struct(&png, &info, &end_info);
    return ReadStatus::ShortData;
  }
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

void onWrite(png_structp png, png_bytep data, png_size_t n) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + n);
}
void onFlush(png_structp) {}

bool writeFrom(std::vector<std::uint8_t>* out, const RawImage& img, WriteState* st) {
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
  png_set_write_fn(png, out, onWrite, onFlush);
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

// PNG's keyword rule (1-79 Latin-1 printable characters, no leading, trailing or double space):
// libpng would otherwise rewrite a bad key while writing, so the file would not say what was asked.
bool validKeyword(const std::string& key) {
  if (key.empty() || key.size() > 79 || key.front() == ' ' || key.back() == ' ') return false;
  for (std::size_t k = 0; k < key.size(); ++k) {
    const unsigned char c = static_cast<unsigned char>(key[k]);
    if (c < 32 || (c > 126 && c < 161) || (c == ' ' && key[k - 1] == ' ')) return false;
  }
  return true;
}

}  // namespace

RawImage readPng(const std::string& path) {
  FilePtr fp(std::fopen(path.c_str(), "rb"));
  if (!fp) throw TextureError(path, "cannot open file", std::strerror(errno), "a readable PNG file");
  // The signature first, so that a device or a huge file of another kind is never read whole.
  std::vector<std::uint8_t> bytes(8);
  bytes.resize(std::fread(bytes.data(), 1, 8, fp.get()));
  if (bytes.size() < 8 || png_sig_cmp(bytes.data(), 0, 8) != 0) return decodePng(bytes, path);
  std::uint8_t chunk[1 << 16];
  for (std::size_t got; (got = std::fread(chunk, 1, sizeof chunk, fp.get())) > 0;)
    bytes.insert(bytes.end(), chunk, chunk + got);
  if (std::ferror(fp.get())) throw TextureError(path, "read failed", std::strerror(errno), "a readable PNG file");
  return decodePng(bytes, path);
}

RawImage decodePng(std::span<const std::uint8_t> bytes, const std::string& path) {
  if (bytes.size() < 8) {
    throw TextureError(path, "not a PNG file", "only " + std::to_string(bytes.size()) + " bytes",
                       "at least the 8-byte PNG signature");
  }
  if (png_sig_cmp(bytes.data(), 0, 8) != 0) {
    throw TextureError(path, "not a PNG file", "wrong signature",
                       "a PNG file (convert JPG, TGA, BMP, TIFF or WebP with texturetool import)");
  }

  if (const std::string overrun = chunkThatOverruns(bytes); !overrun.empty())
    throw TextureError(path, "truncated or corrupt PNG data", overrun, "a complete, valid PNG file");

  auto st = std::make_unique<ReadState>();
  Cursor in{bytes.data(), bytes.size(), 8};
  const ReadStatus status = readInto(&in, st.get());
  const std::string size = std::to_string(st->width) + "x" + std::to_string(st->height);
  switch (status) {
    case ReadStatus::Ok:
      break;
    case ReadStatus::LibpngError:
      throw TextureError(path, "truncated or corrupt PNG data", std::string("libpng: ") + st->sink.message,
                         "a complete, valid PNG file");
    case ReadStatus::ShortData:
      throw TextureError(path, "truncated or corrupt PNG data",
                         size + " needs " + std::to_string(st->needed_bytes) + " bytes of pixel data but only " +
                             std::to_string(bytes.size()) + " bytes are in the file",
                         "at least 1/" + std::to_string(kMaxInflateRatio) +
                             " of the pixel data (zlib's largest compression ratio)");
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

std::vector<std::uint8_t> encodePng(const RawImage& img, const std::string& path) {
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
    if (!validKeyword(key))
      throw TextureError(path, "cannot write a text chunk", "key '" + key + "'",
                         "a PNG keyword: 1-79 printable Latin-1 characters, no leading, trailing or double spaces");
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

  std::vector<std::uint8_t> out;
  if (!writeFrom(&out, img, st.get())) {
    throw TextureError(path, "PNG encoding failed", std::string("libpng: ") + st->sink.message, "a writable image");
  }
  return out;
}

void writePng(const std::string& path, const RawImage& img) {
  const std::vector<std::uint8_t> bytes = encodePng(img, path);
  FilePtr fp(std::fopen(path.c_str(), "wb"));
  if (!fp) throw TextureError(path, "cannot create file", std::strerror(errno), "a writable path");
  if (std::fwrite(bytes.data(), 1, bytes.size(), fp.get()) != bytes.size() || std::fflush(fp.get()) != 0)
    throw TextureError(path, "write failed", std::strerror(errno), "enough disk space");
}

}  // namespace thx::tex
