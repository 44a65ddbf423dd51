// Importing JPEG, BMP, TIFF, WebP and TGA: the fuzz body's seeds and short run
// (image_import_body.hpp), and the bound on TGA pixel memory.
#include <gtest/gtest.h>

#include <set>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "tests/fuzz/fuzz_test_support.hpp"
#include "tests/fuzz/image_import_body.hpp"
#include "tests/textures/bump_images.hpp"

using namespace thx;
using namespace thx::fuzz;

namespace {

const std::string kTarget = "image_import";
constexpr int kN = 8;

Bytes withMode(std::uint8_t mode, const std::vector<std::uint8_t>& file) {
  Bytes b{mode};
  b.insert(b.end(), file.begin(), file.end());
  return b;
}

// The bump (tests/textures/bump_images.hpp) through OpenCV's encoder for `ext`.
std::vector<std::uint8_t> encoded(const std::string& ext, int alpha) {
  const int channels = alpha >= 0 ? 4 : 3;
  const std::vector<std::uint8_t> rgb = tex::test::bumpRgb(kN, false, alpha);
  cv::Mat mat(kN, kN, channels == 4 ? CV_8UC4 : CV_8UC3);
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i)
      for (int c = 0; c < channels; ++c)
        mat.ptr<std::uint8_t>(j)[i * channels + c] =
            rgb[(std::size_t(j) * kN + std::size_t(i)) * std::size_t(channels) + std::size_t(c < 3 ? 2 - c : 3)];
  std::vector<std::uint8_t> out;
  EXPECT_TRUE(cv::imencode(ext, mat, out)) << ext;
  return out;
}

// A TGA of the bump: type 2 (raw) or type 10 (run-length coded, one pixel per raw packet).
std::vector<std::uint8_t> tga(bool rle, int channels) {
  const std::vector<std::uint8_t> rgb = tex::test::bumpRgb(kN, false, channels == 4 ? 200 : -1);
  std::vector<std::uint8_t> b = {0, 0, std::uint8_t(rle ? 10 : 2), 0, 0, 0, 0, 0, 0, 0, 0, 0, kN, 0, kN, 0,
                                 std::uint8_t(8 * channels), std::uint8_t(channels == 4 ? 8 : 0)};
  for (int j = kN - 1; j >= 0; --j)
    for (int i = 0; i < kN; ++i) {
      if (rle) b.push_back(0);  // a raw packet of one pixel
      const std::uint8_t* p = &rgb[(std::size_t(j) * kN + std::size_t(i)) * std::size_t(channels)];
      b.insert(b.end(), {p[2], p[1], p[0]});
      if (channels == 4) b.push_back(p[3]);
    }
  return b;
}

}  // namespace

TEST(FuzzImageImport, WriteSeedCorpusWhenAsked) {
  test::writeSeedsWhenAsked(kTarget, {withMode(0, encoded(".jpg", -1)), withMode(0, encoded(".bmp", -1)),
                                      withMode(2, encoded(".tiff", 100)), withMode(0, encoded(".webp", -1)),
                                      withMode(1, tga(false, 3)), withMode(5, tga(true, 4))});
}

TEST(FuzzImageImport, SeedsHoldTheProperties) { test::expectSeedsHold(&fuzzImageImportOnce, kTarget); }

TEST(FuzzImageImport, CorpusReachesEveryDecoder) {
  // Guards the corpus's value: one seed per decoder, each imported.
  std::set<tex::ImageFormat> formats;
  for (const Bytes& seed : test::corpusOf(kTarget)) {
    const std::string name = (seed[0] & 1) ? "seed.tga" : "seed.img";
    const tex::DecodedImage d = tex::decodeImage(name, std::vector<unsigned char>(seed.begin() + 1, seed.end()));
    formats.insert(d.format);
  }
  EXPECT_EQ(formats.size(), 5u);  // JPEG, BMP, TIFF, WebP, TGA
}

TEST(FuzzImageImport, ShortRun) { test::expectShortRun(&fuzzImageImportOnce, kTarget, 300); }

TEST(FuzzImageImport, TgaPixelMemoryIsBoundedByTheFile) {
  // A 16384^2 run-length TGA header with one packet: refused as truncated from the packet walk,
  // before stb_image allocates 768 MiB.
  std::vector<unsigned char> b = {0, 0, 10, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x40, 0, 0x40, 24, 0, 0xff, 1, 2, 3};
  try {
    tex::decodeImage("huge.tga", b);
    FAIL() << "accepted";
  } catch (const tex::TextureError& e) {
    EXPECT_EQ(e.source(), "huge.tga");
    EXPECT_EQ(e.problem(), "truncated TGA file");
  }
}
