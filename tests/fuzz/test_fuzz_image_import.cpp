// Importing JPEG, BMP, TIFF, WebP and TGA: the fuzz body's seeds and short run
// (image_import_body.hpp), and the bound on TGA pixel memory.
#include <gtest/gtest.h>

#include <set>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "tests/fuzz/seed_writer.hpp"
#include "tests/fuzz/short_run.hpp"
#include "tests/fuzz/image_import_body.hpp"
#include "tests/textures/bump_images.hpp"

namespace test_fuzz_image_import {

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

// A grey w x h image through OpenCV's encoder for `ext` (`params` as imencode takes them).
std::vector<std::uint8_t> grey(const std::string& ext, int w, int h, const std::vector<int>& params = {}) {
  const cv::Mat mat(h, w, CV_8UC3, cv::Scalar(128, 128, 255));
  std::vector<std::uint8_t> out;
  EXPECT_TRUE(cv::imencode(ext, mat, out, params)) << ext;
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

// decodeImage's refusal of `bytes` as "source|problem|value", or "accepted".
std::string refusal(const std::string& name, const std::vector<unsigned char>& bytes,
                    std::int64_t max_pixels = tex::kMaxImagePixels) {
  try {
    tex::decodeImage(name, bytes, max_pixels);
    return "accepted";
  } catch (const tex::TextureError& e) {
    return e.source() + "|" + e.problem() + "|" + e.value();
  }
}

}  // namespace

TEST(FuzzImageImport, WriteSeedCorpusWhenAsked) {
  writeSeedsWhenAsked({withMode(0, encoded(".jpg", -1)), withMode(0, encoded(".bmp", -1)),
                                      withMode(2, encoded(".tiff", 100)), withMode(0, encoded(".webp", -1)),
                                      withMode(1, tga(false, 3)), withMode(5, tga(true, 4))});
}

TEST(FuzzImageImport, SeedsHoldTheProperties) { expectSeedsHold(kTarget, &fuzzImageImportOnce); }

TEST(FuzzImageImport, CorpusReachesEveryDecoder) {
  // Guards the corpus's value: one seed per decoder, each imported.
  std::set<tex::ImageFormat> formats;
  for (const Bytes& seed : loadCorpus(kTarget)) {
    const std::string name = (seed[0] & 1) ? "seed.tga" : "seed.img";
    try {
      formats.insert(tex::decodeImage(name, std::vector<unsigned char>(seed.begin() + 1, seed.end())).format);
    } catch (const tex::TextureError&) {  // regress-*: inputs a run found, refused
    }
  }
  EXPECT_EQ(formats.size(), 5u);  // JPEG, BMP, TIFF, WebP, TGA
}

TEST(FuzzImageImport, ShortRun) { shortRun(kTarget, &fuzzImageImportOnce, 300); }

TEST(FuzzImageImport, MaxPixelsIsReadFromEveryHeader) {
  // The importer's maximum pixel count (texturetool import --max-pixels; the fuzz body's bound) is
  // read from each format's header before decoding: 48 x 20 = 960 pixels, refused at 959.
  std::vector<std::pair<std::string, std::vector<std::uint8_t>>> files = {
      {"a.jpg", grey(".jpg", 48, 20)},
      {"a.bmp", grey(".bmp", 48, 20)},
      {"a.tiff", grey(".tiff", 48, 20)},
      {"lossy.webp", grey(".webp", 48, 20, {cv::IMWRITE_WEBP_QUALITY, 90})},
      {"lossless.webp", grey(".webp", 48, 20, {cv::IMWRITE_WEBP_QUALITY, 101})},
      {"a.png", grey(".png", 48, 20)},
      {"a.tga", {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 48, 0, 20, 0, 24, 0}}};
  files.back().second.resize(18 + 48 * 20 * 3, 0x80);
  for (const auto& [name, bytes] : files) {
    const std::vector<unsigned char> b(bytes.begin(), bytes.end());
    EXPECT_EQ(refusal(name, b, 959), name + "|image too large|48x20 = 960 pixels in its header");  // before decoding
    const tex::DecodedImage d = tex::decodeImage(name, b, 960);
    EXPECT_EQ(d.image.width, 48) << name;
    EXPECT_EQ(d.image.height, 20) << name;
  }
}

TEST(FuzzImageImport, HeaderSidesNearTwoToTheThirtyTwoAreRefused) {
  // Found by libFuzzer (UBSan) in its first 80k inputs, regress-max-pixels-overflow: the first
  // version multiplied a PNG header's two sides of 2^32 - 1 in a signed 64-bit integer.
  const Bytes seed = readBytes(fuzzDir() / "corpus" / "image_import" / "regress-max-pixels-overflow");
  EXPECT_FALSE(fuzzImageImportOnce(seed));
  std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                    0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 8, 2, 0, 0, 0};
  EXPECT_EQ(refusal("huge.png", png), "huge.png|image too large|4294967295x4294967295 = 18446744065119617025 pixels in its header");
}

TEST(FuzzImageImport, AWebPWithoutAnImageHeaderNeverReachesAnotherDecoder) {
  // Found by libFuzzer (out of memory, 2 M executions into the second session's run):
  // regress-webp-read-as-dicom is RIFF/WEBP with a broken first chunk and "DICM" at byte 128, so
  // OpenCV handed it to GDCM's DICOM reader, which allocated from a length field. Refused first.
  const Bytes seed = readBytes(fuzzDir() / "corpus" / "image_import" / "regress-webp-read-as-dicom");
  EXPECT_FALSE(fuzzImageImportOnce(seed));
  const std::vector<unsigned char> file(seed.begin() + 1, seed.end());
  EXPECT_EQ(refusal("a.img", file), "a.img|corrupt WebP header|no VP8, VP8L or VP8X image header at byte 12");
}

TEST(FuzzImageImport, AFileWithADicomSignatureNeverReachesGdcm) {
  // Found by libFuzzer (an abort in GDCM, 0.84 M executions into the third session's run):
  // regress-webp-vp8l-read-as-dicom is RIFF/WEBP with a VP8L header we read but libwebp refuses,
  // and "DICM" at byte 128, so OpenCV tried GDCM's DICOM reader next, which asserted.
  const Bytes seed = readBytes(fuzzDir() / "corpus" / "image_import" / "regress-webp-vp8l-read-as-dicom");
  EXPECT_FALSE(fuzzImageImportOnce(seed));
  const std::vector<unsigned char> file(seed.begin() + 1, seed.end());
  EXPECT_EQ(refusal("a.img", file), "a.img|not a plain WebP file|a DICOM signature (\"DICM\") at byte 128, which "
                                    "OpenCV would hand to its DICOM reader");
  // The same signature in a PNG is refused alike, whatever its format.
  std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  png.resize(132, 0);
  png[128] = 'D', png[129] = 'I', png[130] = 'C', png[131] = 'M';
  EXPECT_EQ(refusal("b.png", png).rfind("b.png|not a plain PNG file|", 0), 0u) << refusal("b.png", png);
}

TEST(FuzzImageImport, TgaPixelMemoryIsBoundedByTheFile) {
  // A 16384^2 run-length TGA header with one packet: refused as truncated from the packet walk,
  // before stb_image allocates 768 MiB.
  std::vector<unsigned char> b = {0, 0, 10, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x40, 0, 0x40, 24, 0, 0xff, 1, 2, 3};
  EXPECT_EQ(refusal("huge.tga", b).rfind("huge.tga|truncated TGA file|", 0), 0u) << refusal("huge.tga", b);
}

}  // namespace test_fuzz_image_import
