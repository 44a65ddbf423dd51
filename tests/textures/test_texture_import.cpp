// texturetool import's library: normal maps in the formats people have (JPEG, BMP, TIFF, WebP
// written here by OpenCV; TGA written by hand), the green conventions, what alpha holds, the
// warnings, and the errors for bad input.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "tests/textures/bump_images.hpp"
#include "textures/generators.hpp"
#include "textures/green_convention.hpp"
#include "textures/import/normal_import.hpp"
#include "textures/texture_error.hpp"

namespace test_texture_import {

using namespace thx::tex;
using namespace thx::tex::test;
namespace fs = std::filesystem;

namespace {

constexpr int kN = 96;

class TextureImport : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("thx_texture_import_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // The bump as an OpenCV image (BGR or BGRA), written with OpenCV's codec for `name`.
  std::string writeBump(const std::string& name, bool directx, int alpha = -1, std::vector<int> params = {}) const {
    const int channels = alpha >= 0 ? 4 : 3;
    const std::vector<std::uint8_t> rgb = bumpRgb(kN, directx, alpha);
    cv::Mat mat(kN, kN, channels == 4 ? CV_8UC4 : CV_8UC3);
    for (int j = 0; j < kN; ++j) {
      for (int i = 0; i < kN; ++i) {
        const std::uint8_t* p = &rgb[(std::size_t(j) * kN + std::size_t(i)) * std::size_t(channels)];
        std::uint8_t* q = mat.ptr<std::uint8_t>(j) + i * channels;
        q[0] = p[2];
        q[1] = p[1];
        q[2] = p[0];
        if (channels == 4) q[3] = p[3];
      }
    }
    const std::string file = path(name);
    EXPECT_TRUE(cv::imwrite(file, mat, params)) << file;
    return file;
  }

  static void truncate(const std::string& file, double keep) {
    fs::resize_file(file, std::size_t(double(fs::file_size(file)) * keep));
  }

  fs::path dir_;
};

auto bump() {
  return [](int i, int j) { return bumpNormal(i, j, kN); };
}

bool anyHas(const std::vector<std::string>& lines, const std::string& part) {
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(part) != std::string::npos; });
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const TextureError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_F(TextureImport, EveryOpenCvFormatGivesTheBumpsNormals) {
  struct Case {
    std::string name;
    std::vector<int> params;
    double max_deg;  // 8-bit rounding alone: about 0.4°
  };
  const std::vector<Case> cases = {
      {"bump.jpg", {cv::IMWRITE_JPEG_QUALITY, 95}, 4.0},
      {"bump75.jpg", {cv::IMWRITE_JPEG_QUALITY, 75}, 8.0},
      {"bump.bmp", {}, 0.5},
      {"bump.tif", {}, 0.5},
      {"bump.webp", {cv::IMWRITE_WEBP_QUALITY, 101}, 0.5},  // > 100: lossless
  };
  const ImageFormat formats[] = {ImageFormat::Jpeg, ImageFormat::Jpeg, ImageFormat::Bmp, ImageFormat::Tiff, ImageFormat::WebP};
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const std::string file = writeBump(cases[k].name, false, -1, cases[k].params);
    ImportReport report;
    const TextureMap map = importNormalMapFile(file, {}, &report);
    EXPECT_EQ(report.format, formats[k]) << file;
    EXPECT_FALSE(map.isRelief());
    const double err = maxAngleDeg(map, bump());
    std::printf("%-10s max angle error %.2f deg, mean |n| %.4f, green score %+.3f\n", cases[k].name.c_str(), err,
                report.mean_length, report.green_guess.score);
    EXPECT_LT(err, cases[k].max_deg) << file;
    EXPECT_TRUE(report.warnings.empty()) << file << ": " << report.warnings.front();
    ASSERT_TRUE(report.green_guess.convention.has_value()) << file;
    EXPECT_EQ(*report.green_guess.convention, GreenConvention::OpenGL) << file << " score " << report.green_guess.score;
  }
}

TEST_F(TextureImport, DirectXGreenIsFlippedAndDetected) {
  const std::string file = writeBump("dx.jpg", true, -1, {cv::IMWRITE_JPEG_QUALITY, 90});
  ImportOptions options;
  options.green = GreenConvention::DirectX;
  ImportReport report;
  const TextureMap map = importNormalMapFile(file, options, &report);
  EXPECT_LT(maxAngleDeg(map, bump()), 5.0);
  EXPECT_TRUE(report.warnings.empty());
  ASSERT_TRUE(report.green_guess.convention.has_value());
  EXPECT_EQ(*report.green_guess.convention, GreenConvention::DirectX);
  EXPECT_GT(report.green_guess.score, 0.8);

  // Read with the wrong convention: the bump's y slopes come out reversed, and the import says so.
  const TextureMap wrong = importNormalMapFile(file, {}, &report);
  EXPECT_NEAR(wrong.normal(kN / 2, kN / 2 - kN / 8).y(), -map.normal(kN / 2, kN / 2 - kN / 8).y(), 0.02);
  std::printf("DirectX JPEG (q90) read as OpenGL: green score %+.3f\n", report.green_guess.score);
  EXPECT_LT(report.green_guess.score, -0.8);
  EXPECT_TRUE(anyHas(report.warnings, "look like directx")) << report.warnings.size();
}

TEST_F(TextureImport, GreenGuessOnGeneratedMapsAndItsLimits) {
  const TextureMap bricks = generate({"bricks", 256, {}, 1});
  GreenGuess g = guessGreenConvention(bricks, GreenConvention::OpenGL);
  ASSERT_TRUE(g.convention.has_value());
  EXPECT_EQ(*g.convention, GreenConvention::OpenGL);
  EXPECT_GT(g.score, 0.8);  // creases (mortar edges) and 16-bit rounding only pull it a little
  g = guessGreenConvention(bricks, GreenConvention::DirectX);  // the same normals, said to be read as DirectX
  ASSERT_TRUE(g.convention.has_value());
  EXPECT_EQ(*g.convention, GreenConvention::DirectX);

  TextureMap grooves(64, 64, Representation::Normal);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) grooves.setNormal(i, j, grooveNormal(i, j, 64));
  g = guessGreenConvention(grooves, GreenConvention::OpenGL);
  EXPECT_FALSE(g.convention.has_value()) << g.score;  // no mixed slopes: cannot tell
  EXPECT_FALSE(guessGreenConvention(TextureMap(8, 8, Representation::Normal), GreenConvention::OpenGL).convention);
}

TEST_F(TextureImport, TgaWithAlphaAsDepthOrHeight) {
  std::vector<std::uint8_t> px = bumpRgb(kN, false, 0);
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) px[(std::size_t(j) * kN + std::size_t(i)) * 4 + 3] = std::uint8_t(i * 255 / (kN - 1));
  const std::string file = path("bump.tga");
  writeTga(file, kN, kN, 4, px);

  ImportOptions options;
  options.alpha = AlphaMeaning::Depth;
  options.alpha_scale_m = 0.002;
  ImportReport report;
  TextureMap map = importNormalMapFile(file, options, &report);
  EXPECT_EQ(report.format, ImageFormat::Tga);
  ASSERT_TRUE(map.isRelief());
  EXPECT_DOUBLE_EQ(map.maxDepth(), 0.002);
  EXPECT_LT(maxAngleDeg(map, bump()), 0.5);  // the rows are the right way up
  EXPECT_NEAR(map.depth(0, 5), 0.0, 1e-9);
  EXPECT_NEAR(map.depth(kN - 1, 5), 0.002, 1e-7);
  EXPECT_TRUE(report.warnings.empty());

  options.alpha = AlphaMeaning::Height;  // white = high: the right edge is the plane
  map = importNormalMapFile(file, options, &report);
  EXPECT_NEAR(map.depth(0, 5), 0.002, 1e-7);
  EXPECT_NEAR(map.depth(kN - 1, 5), 0.0, 1e-9);

  options.alpha = AlphaMeaning::None;  // dropped, with a warning since it varies
  map = importNormalMapFile(file, options, &report);
  EXPECT_FALSE(map.isRelief());
  EXPECT_TRUE(anyHas(report.warnings, "alpha varies (0..255) and was dropped"));
}

TEST_F(TextureImport, ConstantAlphaIsNeverSilentlyADepthMap) {
  const std::string file = writeBump("rgba.png", false, 255);
  ImportReport report;
  TextureMap map = importNormalMapFile(file, {}, &report);  // default: alpha none
  EXPECT_FALSE(map.isRelief());
  EXPECT_TRUE(report.warnings.empty());
  EXPECT_EQ(report.alpha_min, 255);

  ImportOptions options;
  options.alpha = AlphaMeaning::Depth;
  options.alpha_scale_m = 0.001;
  map = importNormalMapFile(file, options, &report);
  EXPECT_TRUE(map.isRelief());
  EXPECT_TRUE(anyHas(report.warnings, "alpha is 255 everywhere")) << report.warnings.size();
  EXPECT_TRUE(anyHas(report.warnings, "--alpha none"));
}

TEST_F(TextureImport, NormalsFarFromUnitLengthWarn) {
  cv::Mat photo(32, 32, CV_8UC3);
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i) photo.at<cv::Vec3b>(j, i) = cv::Vec3b(std::uint8_t(40 + i), std::uint8_t(90), std::uint8_t(200 - j));
  const std::string file = path("photo.bmp");
  ASSERT_TRUE(cv::imwrite(file, photo));
  ImportReport report;
  importNormalMapFile(file, {}, &report);
  EXPECT_GT(report.far_from_unit_fraction, 0.5);
  EXPECT_TRUE(anyHas(report.warnings, "far from unit length"));
}

TEST_F(TextureImport, BadInputNamesTheFile) {
  std::ofstream(path("notes.txt")) << "not an image at all";
  std::string e = errorOf([&] { importNormalMapFile(path("notes.txt"), {}); });
  EXPECT_NE(e.find(path("notes.txt")), std::string::npos) << e;
  EXPECT_NE(e.find("unknown image format"), std::string::npos) << e;
  EXPECT_NE(e.find("TGA"), std::string::npos) << e;

  std::ofstream(path("empty.jpg")).flush();
  EXPECT_NE(errorOf([&] { importNormalMapFile(path("empty.jpg"), {}); }).find("empty file"), std::string::npos);
  EXPECT_NE(errorOf([&] { importNormalMapFile(path("missing.jpg"), {}); }).find("cannot open"), std::string::npos);

  for (const char* name : {"cut.jpg", "cut.bmp", "cut.webp", "cut.tif"}) {
    const std::string file = writeBump(name, false);
    truncate(file, 0.5);
    e = errorOf([&] { importNormalMapFile(file, {}); });
    EXPECT_NE(e.find(file), std::string::npos) << e;
    const bool says_so = e.find("truncated") != std::string::npos || e.find("decoding failed") != std::string::npos;
    EXPECT_TRUE(says_so) << name << ": " << e;
    std::printf("%s\n", e.c_str());
  }

  writeTga(path("cut.tga"), kN, kN, 3, bumpRgb(kN, false), 18 + 1000);
  e = errorOf([&] { importNormalMapFile(path("cut.tga"), {}); });
  EXPECT_NE(e.find("truncated TGA file"), std::string::npos) << e;
  EXPECT_NE(e.find(path("cut.tga")), std::string::npos) << e;

  cv::imwrite(path("gray.jpg"), cv::Mat(16, 16, CV_8UC1, cv::Scalar(100)));
  e = errorOf([&] { importNormalMapFile(path("gray.jpg"), {}); });
  EXPECT_NE(e.find("from-height"), std::string::npos) << e;

  ImportOptions options;
  options.alpha = AlphaMeaning::Depth;
  const std::string rgb = writeBump("rgb.bmp", false);
  e = errorOf([&] { importNormalMapFile(rgb, options); });
  EXPECT_NE(e.find("has no alpha"), std::string::npos) << e;
  const std::string rgba = writeBump("rgba.png", false, 10);
  e = errorOf([&] { importNormalMapFile(rgba, options); });
  EXPECT_NE(e.find("without its scale"), std::string::npos) << e;
  options.alpha_scale_m = -1.0;
  e = errorOf([&] { importNormalMapFile(rgba, options); });
  EXPECT_NE(e.find("alpha scale out of range"), std::string::npos) << e;
}

}  // namespace test_texture_import
