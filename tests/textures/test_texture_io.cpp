// PNG round trips (8/16 bit, normal/relief, green conventions) and the bad-file corpus: every
// bad input gets its own clear error naming the file, the problem, the value and the expectation.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "textures/png_io.hpp"
#include "textures/texture_error.hpp"
#include "textures/texture_io.hpp"

namespace test_texture_io {

using namespace thx::tex;
namespace fs = std::filesystem;

namespace {

class TempDir {
 public:
  TempDir() {
    path_ = fs::temp_directory_path() / ("thx_texio_" + std::to_string(::getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

TextureMap randomRelief(int w, int h, unsigned seed) {
  TextureMap map(w, h, Representation::Relief, 0.0015);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> slope(-2.0f, 2.0f);
  std::uniform_int_distribution<int> code(0, 65535);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      map.setNormal(i, j, {slope(rng), slope(rng), 1.0f});
      map.setDepthCode(i, j, std::uint16_t(code(rng)));
    }
  }
  map.meta().kind = "test";
  map.meta().extent_x_m = 0.1;
  map.meta().extent_y_m = 0.05;
  map.meta().params = "seed=" + std::to_string(seed);
  return map;
}

// Largest angle (radians) between corresponding normals.
double maxAngle(const TextureMap& a, const TextureMap& b) {
  double worst = 0;
  for (int j = 0; j < a.height(); ++j)
    for (int i = 0; i < a.width(); ++i)
    {
      // atan2 of |a x b| and a.b stays accurate for tiny angles, unlike acos(a.b).
      const Eigen::Vector3d na = a.normal(i, j).cast<double>().normalized(), nb = b.normal(i, j).cast<double>().normalized();
      worst = std::max(worst, std::atan2(na.cross(nb).norm(), na.dot(nb)));
    }
  return worst;
}

RawImage solidImage(int w, int h, int channels, int bits, std::vector<std::uint16_t> value) {
  RawImage img;
  img.width = w;
  img.height = h;
  img.channels = channels;
  img.bit_depth = bits;
  for (int k = 0; k < w * h; ++k)
    for (int c = 0; c < channels; ++c) img.samples.push_back(value[std::size_t(c)]);
  return img;
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}
std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

}  // namespace

TEST(TextureIo, RoundTrip16BitRelief) {
  TempDir dir;
  const TextureMap map = randomRelief(33, 17, 1);
  saveTexture(dir.file("r16.png"), map, {16, GreenConvention::OpenGL});
  LoadReport report;
  const TextureMap back = loadTexture(dir.file("r16.png"), {}, &report);
  EXPECT_EQ(report.bit_depth, 16);
  ASSERT_EQ(back.width(), 33);
  ASSERT_EQ(back.height(), 17);
  EXPECT_TRUE(back.isRelief());
  EXPECT_DOUBLE_EQ(back.maxDepth(), 0.0015);
  EXPECT_EQ(back.meta().kind, "test");
  EXPECT_DOUBLE_EQ(back.meta().extent_x_m, 0.1);
  EXPECT_DOUBLE_EQ(back.meta().extent_y_m, 0.05);
  EXPECT_EQ(back.meta().params, "seed=1");
  EXPECT_LT(maxAngle(map, back), 1e-4);  // 16-bit quantisation: ~3e-5 per component
  for (int j = 0; j < 17; ++j)
    for (int i = 0; i < 33; ++i) ASSERT_EQ(back.depthCode(i, j), map.depthCode(i, j));
}

TEST(TextureIo, RoundTrip8BitRelief) {
  TempDir dir;
  const TextureMap map = randomRelief(20, 20, 2);
  saveTexture(dir.file("r8.png"), map, {8, GreenConvention::OpenGL});
  LoadReport report;
  const TextureMap back = loadTexture(dir.file("r8.png"), {}, &report);
  EXPECT_EQ(report.bit_depth, 8);
  // 8-bit: each component within 1/255; for slopes up to 2 the angle error stays under ~0.6 deg.
  EXPECT_LT(maxAngle(map, back), 0.011);
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 20; ++i) ASSERT_NEAR(back.depth(i, j), map.depth(i, j), 0.0015 / 255 / 2 + 1e-9);
}

TEST(TextureIo, RoundTripNormalMapAndGreenConventions) {
  TempDir dir;
  TextureMap map(8, 8, Representation::Normal);
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) map.setNormal(i, j, {0.1f * float(i) - 0.3f, 0.5f, 1.0f});
  saveTexture(dir.file("dx.png"), map, {16, GreenConvention::DirectX});
  const RawImage raw = readPng(dir.file("dx.png"));
  EXPECT_EQ(raw.channels, 3);
  EXPECT_LT(raw.at(0, 0, 1), 32768);  // +y stored as a small green value in DirectX files
  LoadOptions as_dx;
  as_dx.green = GreenConvention::DirectX;
  const TextureMap back = loadTexture(dir.file("dx.png"), as_dx);
  EXPECT_FALSE(back.isRelief());
  EXPECT_LT(maxAngle(map, back), 1e-4);
  LoadReport report;
  const TextureMap flipped = loadTexture(dir.file("dx.png"), {}, &report);
  EXPECT_LT(flipped.normal(3, 3).y(), 0.0f);  // read as OpenGL: green sign flips
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("directx"), std::string::npos);
}

TEST(TextureIo, ReliefFileCanBeReadAsNormalMapAndMaxDepthOverridden) {
  TempDir dir;
  saveTexture(dir.file("r.png"), randomRelief(4, 4, 3));
  LoadOptions as_normal;
  as_normal.representation = Representation::Normal;
  EXPECT_FALSE(loadTexture(dir.file("r.png"), as_normal).isRelief());
  LoadOptions deeper;
  deeper.max_depth_m = 0.01;
  EXPECT_DOUBLE_EQ(loadTexture(dir.file("r.png"), deeper).maxDepth(), 0.01);
}

TEST(TextureIo, RepairPolicyFixesAndCountsBadTexels) {
  TempDir dir;
  RawImage img = solidImage(4, 4, 3, 8, {128, 128, 255});
  img.samples[(1 * 4 + 2) * 3 + 2] = 128;  // texel (2,1): (0,0,0) degenerate
  img.samples[(3 * 4 + 0) * 3 + 2] = 0;    // texel (0,3): z = -1, into the surface
  writePng(dir.file("bad.png"), img);
  LoadOptions repair;
  repair.bad_texels = BadTexelPolicy::Repair;
  LoadReport report;
  const TextureMap map = loadTexture(dir.file("bad.png"), repair, &report);
  EXPECT_EQ(report.degenerate_texels, 1);
  EXPECT_EQ(report.into_surface_texels, 1);
  EXPECT_EQ(report.repaired_texels, 2);
  EXPECT_GT(map.normal(2, 1).z(), 0.99f);
  EXPECT_GT(map.normal(0, 3).z(), 0.99f);
}

// ---- the bad-file corpus ----------------------------------------------------------------------

struct BadCase {
  std::string name;
  std::vector<std::string> must_contain;
};

class BadFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string good = dir.file("good.png");
    saveTexture(good, randomRelief(16, 16, 4));
    const std::string bytes = readBytes(good);

    writeBytes(dir.file("empty.png"), "");
    writeBytes(dir.file("text.png"), "this is not an image, it is a text file\n");
    writeBytes(dir.file("truncated.png"), bytes.substr(0, bytes.size() / 2));
    std::string corrupt = bytes;
    const auto idat = corrupt.find("IDAT");
    corrupt[idat + 10] = char(corrupt[idat + 10] ^ 0x5a);  // breaks the chunk CRC
    writeBytes(dir.file("corrupt.png"), corrupt);
    writePng(dir.file("gray.png"), solidImage(4, 4, 1, 8, {200}));
    writePng(dir.file("gray_alpha.png"), solidImage(4, 4, 2, 16, {200, 7}));
    writePng(dir.file("tiny.png"), solidImage(1, 5, 3, 8, {128, 128, 255}));
    writePng(dir.file("huge.png"), solidImage(16385, 2, 3, 8, {128, 128, 255}));
    RawImage degenerate = solidImage(5, 3, 3, 8, {128, 128, 255});
    degenerate.samples[(1 * 5 + 3) * 3 + 2] = 128;
    writePng(dir.file("degenerate.png"), degenerate);
    RawImage inward = solidImage(5, 3, 3, 8, {128, 128, 255});
    inward.samples[(2 * 5 + 4) * 3 + 2] = 10;
    writePng(dir.file("inward.png"), inward);
    writePng(dir.file("relief_no_depth.png"), solidImage(4, 4, 4, 8, {128, 128, 255, 10}));
    RawImage bad_depth = solidImage(4, 4, 4, 8, {128, 128, 255, 10});
    bad_depth.text["thx.max_depth_m"] = "abc";
    writePng(dir.file("relief_bad_depth.png"), bad_depth);
    RawImage negative_depth = bad_depth;
    negative_depth.text["thx.max_depth_m"] = "-0.001";
    writePng(dir.file("relief_negative_depth.png"), negative_depth);
    writePng(dir.file("normal_only.png"), solidImage(4, 4, 3, 8, {128, 128, 255}));
  }

  std::string load(const std::string& name, LoadOptions options = {}) {
    try {
      loadTexture(dir.file(name), options);
    } catch (const TextureError& e) {
      EXPECT_EQ(e.source(), dir.file(name));
      return e.what();
    }
    ADD_FAILURE() << name << " was accepted";
    return {};
  }

  TempDir dir;
};

TEST_F(BadFiles, EachGivesItsOwnClearError) {
  const std::vector<BadCase> cases = {
      {"missing.png", {"missing.png", "cannot open file", "No such file"}},
      {"empty.png", {"not a PNG file", "only 0 bytes", "signature"}},
      {"text.png", {"not a PNG file", "wrong signature"}},
      {"truncated.png", {"truncated or corrupt", "chunk 'IDAT'", "but 930 follow"}},
      {"corrupt.png", {"truncated or corrupt", "libpng: IDAT"}},
      {"gray.png", {"wrong channel count", "1 channel (grayscale)", "3 channels (RGB normal map) or 4"}},
      {"gray_alpha.png", {"wrong channel count", "2 channels"}},
      {"tiny.png", {"image too small", "1x5", "at least 2x2"}},
      {"huge.png", {"image too large", "16385x2", "at most 16384x16384"}},
      {"degenerate.png", {"1 bad texel", "1 degenerate", "texel (3, 1)", "RGB (128, 128, 128)", "length 0.5..1.5"}},
      {"inward.png", {"pointing into the surface", "texel (4, 2)", "RGB (128, 128, 10)", "z > 0"}},
      {"relief_no_depth.png", {"no maximum depth", "thx.max_depth_m", "max_depth"}},
      {"relief_bad_depth.png", {"bad 'thx.max_depth_m'", "'abc'", "> 0 in metres"}},
      {"relief_negative_depth.png", {"bad 'thx.max_depth_m'", "'-0.001'"}},
  };
  for (const BadCase& c : cases) {
    const std::string message = load(c.name);
    for (const std::string& part : c.must_contain) {
      EXPECT_NE(message.find(part), std::string::npos) << c.name << ": '" << message << "' lacks '" << part << "'";
    }
  }
}

TEST_F(BadFiles, OptionsThatContradictTheFile) {
  LoadOptions want_relief;
  want_relief.representation = Representation::Relief;
  const std::string m1 = load("normal_only.png", want_relief);
  EXPECT_NE(m1.find("a relief map was asked for"), std::string::npos) << m1;
  LoadOptions nan_depth;
  nan_depth.max_depth_m = std::nan("");
  const std::string m2 = load("good.png", nan_depth);
  EXPECT_NE(m2.find("maximum depth override"), std::string::npos) << m2;
  EXPECT_NE(m2.find("nan"), std::string::npos) << m2;
}

TEST(TextureMapValidation, RejectsBadSizesAndValues) {
  EXPECT_THROW(TextureMap(1, 4, Representation::Normal), TextureError);
  EXPECT_THROW(TextureMap(4, 16385, Representation::Normal), TextureError);
  EXPECT_THROW(TextureMap(4, 4, Representation::Relief, 0.0), TextureError);
  EXPECT_THROW(TextureMap(4, 4, Representation::Relief, std::nan("")), TextureError);
  TextureMap map(4, 4, Representation::Relief, 0.001);
  EXPECT_THROW(map.setNormal(1, 1, {std::nanf(""), 0, 1}), TextureError);
  EXPECT_THROW(map.setNormal(1, 1, {0, 0, 0}), TextureError);
  EXPECT_THROW(map.setNormal(1, 1, {0, 0.2f, -1}), TextureError);
  EXPECT_THROW(map.setDepth(1, 1, INFINITY), TextureError);
  try {
    map.setNormal(2, 3, {0, 1, -0.5f});
    FAIL();
  } catch (const TextureError& e) {
    EXPECT_NE(std::string(e.what()).find("texel (2, 3)"), std::string::npos) << e.what();
  }
  map.setDepth(0, 0, 0.5);  // clamps to the maximum depth
  EXPECT_FLOAT_EQ(map.depth(0, 0), 0.001f);
  map.setDepth(0, 0, -1.0);
  EXPECT_FLOAT_EQ(map.depth(0, 0), 0.0f);
}

}  // namespace test_texture_io
