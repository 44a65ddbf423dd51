#include "textures/import/tga_decode.hpp"

#include <stb_image.h>

#include <cstdint>
#include <memory>

#include "textures/texture_error.hpp"
#include "textures/texture_map.hpp"

namespace thx::tex {

namespace {

constexpr std::size_t kHeaderBytes = 18;

unsigned u16(const std::vector<unsigned char>& b, std::size_t at) { return unsigned(b[at]) | unsigned(b[at + 1]) << 8; }

struct TgaHeader {
  unsigned id_length, colour_map_type, image_type, map_length, map_entry_bits, width, height, bits;
  bool rle() const { return image_type >= 9; }
  std::size_t bytesPerPixel() const { return (bits + 7) / 8; }
  std::size_t dataStart() const {
    return kHeaderBytes + id_length + (colour_map_type ? std::size_t(map_length) * ((map_entry_bits + 7) / 8) : 0);
  }
};

TgaHeader readHeader(const std::vector<unsigned char>& b) {
  return {b[0], b[1], b[2], u16(b, 5), b[7], u16(b, 12), u16(b, 14), b[16]};
}

// Bytes of pixel data the header promises, walking the run-length packets of an RLE image;
// 0 when the data ends before the last pixel.
std::size_t pixelDataEnd(const TgaHeader& h, const std::vector<unsigned char>& b) {
  const std::size_t start = h.dataStart(), pixel_bytes = h.bytesPerPixel();
  const std::size_t pixels = std::size_t(h.width) * h.height;
  if (!h.rle()) return start + pixels * pixel_bytes;
  std::size_t at = start, done = 0;
  while (done < pixels) {
    if (at >= b.size()) return 0;
    const unsigned packet = b[at++];
    const std::size_t count = (packet & 0x7f) + 1;
    at += (packet & 0x80) ? pixel_bytes : count * pixel_bytes;
    done += count;
  }
  return at;
}

}  // namespace

bool looksLikeTga(const std::vector<unsigned char>& b) {
  if (b.size() < kHeaderBytes) return false;
  const TgaHeader h = readHeader(b);
  const bool known_type = h.image_type == 1 || h.image_type == 2 || h.image_type == 3 || h.image_type == 9 ||
                          h.image_type == 10 || h.image_type == 11;
  const bool known_bits = h.bits == 8 || h.bits == 15 || h.bits == 16 || h.bits == 24 || h.bits == 32;
  return known_type && known_bits && h.colour_map_type <= 1 && h.width > 0 && h.height > 0;
}

RawImage decodeTga(const std::string& path, const std::vector<unsigned char>& bytes) {
  if (!looksLikeTga(bytes)) {
    throw TextureError(path, "not a TGA file this reader knows", "an unreadable 18-byte header",
                       "TGA image type 1, 2, 3, 9, 10 or 11 with 8, 15, 16, 24 or 32 bits per pixel");
  }
  const TgaHeader h = readHeader(bytes);
  const std::string size = std::to_string(h.width) + "x" + std::to_string(h.height);
  if (int(h.width) < kMinTextureSide || int(h.height) < kMinTextureSide || int(h.width) > kMaxTextureSide ||
      int(h.height) > kMaxTextureSide) {
    throw TextureError(path, "image size out of range", size,
                       "each side in [" + std::to_string(kMinTextureSide) + ", " + std::to_string(kMaxTextureSide) + "]");
  }
  const std::size_t end = pixelDataEnd(h, bytes);
  if (end == 0 || end > bytes.size()) {
    throw TextureError(path, "truncated TGA file", std::to_string(bytes.size()) + " bytes",
                       "the header and " + size + " pixels of " + std::to_string(h.bits) + " bits" +
                           (h.rle() ? " (run-length coded)" : ""));
  }
  int w = 0, hgt = 0, channels = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &hgt, &channels, 0), stbi_image_free);
  if (!pixels) throw TextureError(path, "TGA decoding failed", std::string("stb_image: ") + stbi_failure_reason(), "a valid TGA file");
  RawImage image;
  image.width = w;
  image.height = hgt;
  image.channels = channels;
  image.bit_depth = 8;
  image.samples.assign(pixels.get(), pixels.get() + std::size_t(w) * std::size_t(hgt) * std::size_t(channels));
  return image;
}

}  // namespace thx::tex
