// PNG textures: the fuzz body's seeds and short run (png_texture_body.hpp), and the bound on pixel
// memory a PNG header can ask for.
#include <gtest/gtest.h>

#include "tests/fuzz/seed_writer.hpp"
#include "tests/fuzz/short_run.hpp"
#include "tests/fuzz/png_texture_body.hpp"
#include "textures/generators.hpp"

namespace test_fuzz_png_texture {

using namespace thx;
using namespace thx::fuzz;

namespace {

const std::string kTarget = "png_texture";

Bytes withMode(std::uint8_t mode, const std::vector<std::uint8_t>& file) {
  Bytes b{mode};
  b.insert(b.end(), file.begin(), file.end());
  return b;
}

// A PNG chunk with its length and CRC.
void appendChunk(Bytes& b, const char type[4], const Bytes& data) {
  const std::uint32_t n = std::uint32_t(data.size());
  for (int k = 0; k < 4; ++k) b.push_back(std::uint8_t(n >> (24 - 8 * k)));
  const std::size_t start = b.size();
  b.insert(b.end(), type, type + 4);
  b.insert(b.end(), data.begin(), data.end());
  const std::uint32_t crc = png_detail::crc32(b.data() + start, 4 + data.size());
  for (int k = 0; k < 4; ++k) b.push_back(std::uint8_t(crc >> (24 - 8 * k)));
}

// Generated textures in every layout the writer has, plus gray and gray+alpha images.
std::vector<Bytes> generatedSeeds() {
  std::vector<Bytes> seeds;
  tex::GenerateRequest bricks{"bricks", 8, {}, 1};
  const tex::TextureMap relief = tex::generate(bricks);
  tex::GenerateRequest sine{"sine", 8, {}, 1};
  tex::TextureMap normal(8, 8, tex::Representation::Normal);
  const tex::TextureMap s = tex::generate(sine);
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) normal.setNormal(i, j, s.normal(i, j));
  normal.meta().extent_x_m = normal.meta().extent_y_m = 0.05;
  for (int depth : {8, 16}) {
    tex::SaveOptions save;
    save.bit_depth = depth;
    seeds.push_back(withMode(1, tex::encodePng(tex::encodeTexture(relief, "seed", save), "seed")));
    save.green = tex::GreenConvention::DirectX;
    seeds.push_back(withMode(3, tex::encodePng(tex::encodeTexture(normal, "seed", save), "seed")));
  }
  for (int channels : {1, 2}) {
    tex::RawImage gray;
    gray.width = gray.height = 4;
    gray.channels = channels;
    gray.samples.assign(std::size_t(16 * channels), 200);
    seeds.push_back(withMode(0, tex::encodePng(gray, "seed")));
  }
  return seeds;
}

}  // namespace

TEST(FuzzPngTexture, WriteSeedCorpusWhenAsked) { writeSeedsWhenAsked(generatedSeeds()); }

TEST(FuzzPngTexture, SeedsHoldTheProperties) { expectSeedsHold(kTarget, &fuzzPngTextureOnce); }

TEST(FuzzPngTexture, CorpusReachesTheTextureRoundTrip) {
  // Guards the corpus's value: seeds that stopped loading as textures would leave that path unfuzzed.
  int textures = 0;
  for (const Bytes& seed : loadCorpus(kTarget)) {
    try {
      tex::LoadOptions load;
      if (seed[0] & 2) load.green = tex::GreenConvention::DirectX;
      tex::decodeTexture(tex::decodePng(std::span(seed).subspan(1), "seed"), "seed", load);
      ++textures;
    } catch (const tex::TextureError&) {
    }
  }
  EXPECT_GE(textures, 4);
}

TEST(FuzzPngTexture, ShortRun) { shortRun(kTarget, &fuzzPngTextureOnce, 300); }

TEST(FuzzPngTexture, RefusesPixelDataTheFileCannotHold) {
  // A 16384^2 RGBA 16-bit header (2 GiB of pixels) with a few bytes of data: refused from the
  // header and the file size, before the pixel memory is allocated.
  Bytes png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  appendChunk(png, "IHDR", {0, 0, 0x40, 0, 0, 0, 0x40, 0, 16, 6, 0, 0, 0});
  appendChunk(png, "IDAT", {0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01});
  appendChunk(png, "IEND", {});
  try {
    tex::decodePng(png, "huge.png");
    FAIL() << "accepted";
  } catch (const tex::TextureError& e) {
    EXPECT_EQ(e.source(), "huge.png");
    EXPECT_EQ(e.problem(), "truncated or corrupt PNG data");
    EXPECT_NE(e.value().find("16384x16384 needs 2147483648 bytes"), std::string::npos) << e.value();
  }
}

TEST(FuzzPngTexture, RefusesAChunkLongerThanTheFile) {
  // Found by the short run: a tEXt chunk stating 1.3 GB in a 213-byte file made libpng allocate and
  // clear 1.3 GB (3 s) before failing. The input is corpus/png_texture/regress-text-chunk-length.
  const Bytes seed = readBytes(fuzzDir() / "corpus" / "png_texture" / "regress-text-chunk-length");
  Bytes file(seed.begin() + 1, seed.end());
  png_detail::fixChunkCrcs(file);
  try {
    tex::decodePng(file, "long.png");
    FAIL() << "accepted";
  } catch (const tex::TextureError& e) {
    EXPECT_EQ(e.source(), "long.png");
    EXPECT_EQ(e.value(), "chunk 'tEXt' at byte 33 states 1314062390 bytes of data but 168 follow");
  }
}

TEST(FuzzPngTexture, BoundKeepsHighlyCompressedImages) {
  // A constant 1024^2 RGB image compresses far beyond 100:1; it is within zlib's bound and loads.
  tex::RawImage flat;
  flat.width = flat.height = 1024;
  flat.channels = 3;
  flat.samples.assign(std::size_t(1024) * 1024 * 3, 128);
  const std::vector<std::uint8_t> png = tex::encodePng(flat, "flat.png");
  EXPECT_LT(png.size() * 100, flat.samples.size());
  EXPECT_EQ(tex::decodePng(png, "flat.png").samples, flat.samples);
}

}  // namespace test_fuzz_png_texture
