#pragma once
// One fuzzing step for PNG textures: libpng through decodePng, then the `thx.*` text chunks and the
// texel checks of decodeTexture. Shared by the libFuzzer target (libfuzzer/png_texture.cpp) and the
// short run in test_fuzz_png_texture.cpp.
//
// Input: byte 0 picks the mode (bit 0: recompute every chunk's CRC, so mutations reach the chunk
// parsers instead of stopping at the CRC check; bit 1: DirectX green; bit 2: depth override; bit 3:
// repair bad texels), the rest is the file. Properties:
//  1. a refused file raises TextureError naming the file;
//  2. an accepted image is consistent (size within the texture limits, 1-4 channels, 8 or 16 bits,
//     samples matching, each within the bit depth) and survives encodePng -> decodePng unchanged
//     (size, layout, samples, text chunks), unless a text key read from the file is not a PNG
//     keyword, which encodePng refuses rather than rewrite;
//  3. decodeTexture refuses with a TextureError naming the file, or gives a map the image's size
//     whose saved form (encodeTexture at the same bit depth) loads again with the Reject policy to
//     the same size, representation, maximum depth, depth codes, metadata and normals within
//     the quantisation of that bit depth (x and y within 4/max + 1e-4; z follows from them).
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>

#include "tests/fuzz/raw_image_checks.hpp"
#include "tests/fuzz/failure.hpp"
#include "textures/png_io.hpp"
#include "textures/texture_error.hpp"
#include "textures/texture_io.hpp"

namespace thx::fuzz {

inline constexpr const char* kPngSource = "fuzz.png";

namespace png_detail {

inline std::uint32_t crc32(const std::uint8_t* p, std::size_t n) {
  static const auto table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t k = 0; k < 256; ++k) {
      std::uint32_t c = k;
      for (int b = 0; b < 8; ++b) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[k] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xffffffffu;
  for (std::size_t k = 0; k < n; ++k) c = table[(c ^ p[k]) & 0xff] ^ (c >> 8);
  return c ^ 0xffffffffu;
}

// Rewrites the CRC of every whole chunk after the signature.
inline void fixChunkCrcs(Bytes& b) {
  std::size_t at = 8;
  while (at + 12 <= b.size()) {
    const std::size_t len = std::size_t(b[at]) << 24 | std::size_t(b[at + 1]) << 16 | std::size_t(b[at + 2]) << 8 | b[at + 3];
    if (len > b.size() - at - 12) break;
    const std::uint32_t crc = crc32(b.data() + at + 4, 4 + len);
    for (int k = 0; k < 4; ++k) b[at + 8 + len + std::size_t(k)] = std::uint8_t(crc >> (24 - 8 * k));
    at += 12 + len;
  }
}

inline Failure sameImage(const tex::RawImage& a, const tex::RawImage& b) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels || a.bit_depth != b.bit_depth)
    return std::string("PNG round trip changed the layout");
  if (a.samples != b.samples) return std::string("PNG round trip changed the samples");
  if (a.text != b.text) return std::string("PNG round trip changed the text chunks");
  return std::nullopt;
}

inline Failure checkTextureRoundTrip(const tex::TextureMap& map, const tex::RawImage& raw, const tex::LoadOptions& load) {
  if (map.width() != raw.width || map.height() != raw.height) return std::string("texture size differs from the image");
  tex::SaveOptions save;
  save.bit_depth = raw.bit_depth;
  save.green = load.green;
  const tex::RawImage saved = tex::encodeTexture(map, kPngSource, save);
  tex::LoadOptions again;
  again.green = load.green;
  tex::TextureMap back;
  try {
    back = tex::decodeTexture(tex::decodePng(tex::encodePng(saved, kPngSource), kPngSource), kPngSource, again);
  } catch (const tex::TextureError& e) {
    return std::string("a saved texture does not load again: ") + e.what();
  }
  if (back.width() != map.width() || back.height() != map.height() || back.representation() != map.representation() ||
      back.maxDepth() != map.maxDepth())
    return std::string("texture round trip changed size, representation or maximum depth");
  const tex::TextureMeta &m = map.meta(), &n = back.meta();
  if (m.kind != n.kind || m.params != n.params || m.extent_x_m != n.extent_x_m || m.extent_y_m != n.extent_y_m)
    return std::string("texture round trip changed the metadata");
  // The map stores x and y (z follows from them), so those are compared: each decoded component
  // is off by at most half a code (1/max), renormalising moves it by at most sqrt(3)/max, lifting
  // z above the plane by at most 1/max more, and x and y are stored as snorm16 twice. Comparing z
  // would not work: at a grazing normal it is sqrt(1 - x^2 - y^2) and amplifies those errors
  // (found by fuzz_png_texture: a repaired texel at z = 0.001 came back at 0.005).
  const float tolerance = 4.0f / float(raw.maxValue()) + 1e-4f;
  for (int j = 0; j < map.height(); ++j)
    for (int i = 0; i < map.width(); ++i) {
      const Eigen::Vector3f a = map.normal(i, j), b = back.normal(i, j);
      if (std::fabs(a.x() - b.x()) > tolerance || std::fabs(a.y() - b.y()) > tolerance)
        return "texture round trip moved the normal of texel (" + std::to_string(i) + ", " + std::to_string(j) + ")";
      if (map.isRelief() && back.depthCode(i, j) != map.depthCode(i, j))
        return "texture round trip changed the depth of texel (" + std::to_string(i) + ", " + std::to_string(j) + ")";
    }
  return std::nullopt;
}

}  // namespace png_detail

inline Failure fuzzPngTextureOnce(std::span<const std::uint8_t> data) {
  if (data.empty()) return std::nullopt;
  const std::uint8_t mode = data[0];
  Bytes file(data.begin() + 1, data.end());
  if (mode & 1) png_detail::fixChunkCrcs(file);

  tex::RawImage raw;
  try {
    raw = tex::decodePng(file, kPngSource);
  } catch (const tex::TextureError& e) {
    if (e.source() != kPngSource) return "TextureError with source '" + e.source() + "'";
    return mustName(e.what(), kPngSource, "PNG refusal");
  }
  if (Failure f = checkRawImage(raw)) return f;
  try {
    if (Failure f = png_detail::sameImage(raw, tex::decodePng(tex::encodePng(raw, kPngSource), kPngSource))) return f;
  } catch (const tex::TextureError& e) {
    // The one refusal allowed: a text key read from the file that PNG does not allow to be written.
    if (e.problem() != "cannot write a text chunk")
      return std::string("an accepted image does not survive encodePng/decodePng: ") + e.what();
  }

  tex::LoadOptions load;
  load.green = (mode & 2) ? tex::GreenConvention::DirectX : tex::GreenConvention::OpenGL;
  if (mode & 4) load.max_depth_m = 0.002;
  load.bad_texels = (mode & 8) ? tex::BadTexelPolicy::Repair : tex::BadTexelPolicy::Reject;
  tex::TextureMap map;
  tex::LoadReport report;
  try {
    map = tex::decodeTexture(raw, kPngSource, load, &report);
  } catch (const tex::TextureError& e) {
    if (e.source() != kPngSource) return "TextureError with source '" + e.source() + "'";
    return mustName(e.what(), kPngSource, "texture refusal");
  }
  if (load.bad_texels == tex::BadTexelPolicy::Reject && report.degenerate_texels + report.into_surface_texels > 0)
    return std::string("the Reject policy accepted bad texels");
  for (const std::string& w : report.warnings)
    if (Failure f = mustName(w, kPngSource, "warning")) return f;
  return png_detail::checkTextureRoundTrip(map, raw, load);
}

}  // namespace thx::fuzz
