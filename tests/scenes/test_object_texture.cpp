// objects[].texture (issue 29): a relief map on a box's faces, parsed with the surface texture's
// rules, its tile defaulted from the generator's extent or the box, built by buildObjectTexture;
// a file of normals only read as the relief they integrate to; misplaced or unusable textures
// are errors naming the object.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "scenes/scene_loader.hpp"
#include "scenes/surface_texture.hpp"
#include "tests/support/block_grooves.hpp"
#include "tests/support/temp_dir.hpp"
#include "textures/generators.hpp"
#include "textures/texture_io.hpp"

namespace test_object_texture {

namespace {

using namespace thx::scene;
namespace tex = thx::tex;

std::string withObject(const std::string& object) {
  return "version: 1\nname: t\nsurface:\n  size: [0.1, 0.1]\n  texture: {generator: bricks, size: 32}\n"
         "objects:\n  - " +
         object + "\n";
}

Scene parse(const std::string& text) { return parseScene(text, "t.yaml", ""); }

void expectError(const std::string& text, const std::string& field, const std::vector<std::string>& words) {
  try {
    parse(text);
    FAIL() << "no error for " << text;
  } catch (const SceneError& e) {
    EXPECT_EQ(e.field(), field) << e.what();
    for (const std::string& w : words) EXPECT_NE(std::string(e.what()).find(w), std::string::npos) << e.what();
  }
}

TEST(ObjectTexture, AGeneratorsExtentIsTheTile) {
  const Scene scene = parse(withObject(
      "{name: block, shape: box, size: [0.04, 0.03, 0.01], mass: 0.05, position: [0, 0, 0.005],\n"
      "     texture: {generator: grooves, size: 64, params: {extent: 0.016}}}"));
  ASSERT_TRUE(scene.objects[0].texture);
  EXPECT_DOUBLE_EQ(scene.objects[0].texture->tile_m, 0.016);
  EXPECT_EQ(scene.objects[0].texture->source.kind, TextureSource::Kind::Generator);
  const tex::TextureMap map = buildObjectTexture(scene, 0);
  EXPECT_TRUE(map.isRelief());
  EXPECT_EQ(map.width(), 64);
  EXPECT_DOUBLE_EQ(map.meta().extent_x_m, 0.016);
}

TEST(ObjectTexture, WithoutExtentOrTileTheTextureSpansTheLongestEdge) {
  const Scene scene = parse(withObject(
      "{name: block, shape: box, size: [0.04, 0.03, 0.01], mass: 0.05, position: [0, 0, 0.005],\n"
      "     texture: {generator: grooves, size: 32}}"));
  EXPECT_DOUBLE_EQ(scene.objects[0].texture->tile_m, 0.04);
  // The generator's extent follows the tile, so its normals match its depth at that scale.
  EXPECT_DOUBLE_EQ(scene.objects[0].texture->source.generator.params.at("extent"), 0.04);
}

TEST(ObjectTexture, AnExplicitTileSetsTheExtentToo) {
  const Scene scene = parse(withObject(
      "{name: block, shape: box, size: [0.04, 0.03, 0.01], mass: 0.05, position: [0, 0, 0.005],\n"
      "     texture: {generator: grooves, size: 32}, texture_tile: 0.01}"));
  EXPECT_DOUBLE_EQ(scene.objects[0].texture->tile_m, 0.01);
  EXPECT_DOUBLE_EQ(scene.objects[0].texture->source.generator.params.at("extent"), 0.01);
}

TEST(ObjectTexture, UntexturedObjectsHaveNone) {
  const Scene scene =
      parse(withObject("{name: ball, shape: sphere, radius: 0.01, mass: 0.05, position: [0, 0, 0.01]}"));
  EXPECT_FALSE(scene.objects[0].texture);
}

TEST(ObjectTexture, OnlyABoxOrASphereCarriesATexture) {
  expectError(withObject("{name: rod, shape: capsule, radius: 0.01, length: 0.03, mass: 0.05, position: [0, 0, 0.01],\n"
                         "     texture: {generator: grooves}}"),
              "objects[0].texture", {"only a box or a sphere carries a texture", "no texture on a capsule"});
}

TEST(ObjectTexture, ABallsTileDefaultsToOneFaceOfItsCube) {
  // meshes/textured_ball_mesh.hpp: each of the six faces spans pi r / 2 along its edges.
  const Scene scene = parse(withObject("{name: ball, shape: sphere, radius: 0.01, mass: 0.05, position: [0, 0, 0.01],\n"
                                       "     texture: {generator: dimples, size: 32}}"));
  ASSERT_TRUE(scene.objects[0].texture);
  EXPECT_DOUBLE_EQ(scene.objects[0].texture->tile_m, 0.5 * std::numbers::pi * 0.01);
}

TEST(ObjectTexture, ATileNeedsATexture) {
  expectError(withObject("{name: block, shape: box, size: [0.04, 0.03, 0.01], mass: 0.05, position: [0, 0, 0.005],\n"
                         "     texture_tile: 0.01}"),
              "objects[0].texture_tile", {"a texture tile without a texture", "texture: {generator"});
}

TEST(ObjectTexture, AnUnknownGeneratorIsNamed) {
  expectError(withObject("{name: block, shape: box, size: [0.04, 0.03, 0.01], mass: 0.05, position: [0, 0, 0.005],\n"
                         "     texture: {generator: groves}}"),
              "objects[0].texture.generator", {"unknown generator", "grooves"});
}

tex::TextureMap normalsOf(const tex::TextureMap& relief) {
  tex::TextureMap normals(relief.width(), relief.height(), tex::Representation::Normal);
  for (int j = 0; j < relief.height(); ++j)
    for (int i = 0; i < relief.width(); ++i) normals.setNormal(i, j, relief.normal(i, j));
  return normals;
}

std::string boxWithFile(const std::string& file) {
  return withObject("{name: block, shape: box, size: [0.04, 0.03, 0.01], mass: 0.05, position: [0, 0, 0.005],\n"
                    "     texture: {file: " + file + "}, texture_tile: 0.02}");
}

// The largest and the RMS difference between two reliefs' depths, each less its mean.
struct DepthDifference {
  double worst = 0.0, rms = 0.0;
};
DepthDifference depthDifference(const tex::TextureMap& a, const tex::TextureMap& b) {
  const int n = a.width() * a.height();
  double mean_a = 0.0, mean_b = 0.0;
  for (int j = 0; j < a.height(); ++j)
    for (int i = 0; i < a.width(); ++i) mean_a += double(a.depth(i, j)) / n, mean_b += double(b.depth(i, j)) / n;
  DepthDifference d;
  for (int j = 0; j < a.height(); ++j)
    for (int i = 0; i < a.width(); ++i) {
      const double e = (double(a.depth(i, j)) - mean_a) - (double(b.depth(i, j)) - mean_b);
      d.worst = std::max(d.worst, std::fabs(e));
      d.rms += e * e / n;
    }
  d.rms = std::sqrt(d.rms);
  return d;
}

// Normals read from `file` as the block's texture (a 2 cm tile), with the report's warnings.
tex::TextureMap objectTextureFrom(const std::string& file, tex::LoadReport& report) {
  const Scene scene = parse(boxWithFile(file));
  SurfaceTextureOptions options;
  options.report = &report;
  return buildObjectTexture(scene, 0, options);
}

// A file of normals only becomes the relief they integrate to at the object's tile: heights whose
// normals are their central differences (the project's heights-to-normals rule) come back to the
// file's 16 bits.
TEST(ObjectTexture, ANormalMapFileIsReadAsTheReliefItsNormalsIntegrateTo) {
  const thx::test::TempDir files("thx_object_tex");
  const tex::TextureMap relief = thx::test::centralDifferenceBlockGrooves(tex::Representation::Relief);
  const std::string file = files.file("normals.png");
  tex::saveTexture(file, normalsOf(relief));
  tex::LoadReport report;
  const tex::TextureMap map = objectTextureFrom(file, report);
  ASSERT_TRUE(map.isRelief());
  ASSERT_EQ(map.width(), 64);
  ASSERT_EQ(map.height(), 64);
  EXPECT_TRUE(report.warnings.empty());  // grooves are level on average
  const DepthDifference d = depthDifference(map, relief);
  std::printf("[measured] grooves 0.8 mm deep from their central-difference normals: depth within %.2f um (RMS %.2f)\n",
              d.worst * 1e6, d.rms * 1e6);
  EXPECT_LT(d.worst, 0.005 * 0.0008);
}

// A generator's normals are its profile's exact slopes, not central differences: read back as a
// relief they give a profile a little off the generator's depth (the least-squares heights of
// central differences that match them), measured here on the shipped grooved block's grooves.
TEST(ObjectTexture, AGeneratorsExactSlopesIntegrateCloseToItsDepth) {
  const thx::test::TempDir files("thx_object_tex");
  const tex::TextureMap relief = thx::test::generatedBlockGrooves();
  const std::string file = files.file("normals.png");
  tex::saveTexture(file, normalsOf(relief));
  tex::LoadReport report;
  const DepthDifference d = depthDifference(objectTextureFrom(file, report), relief);
  std::printf("[measured] grooves 0.8 mm deep from their exact slopes: depth within %.1f um (RMS %.1f)\n",
              d.worst * 1e6, d.rms * 1e6);
  EXPECT_LT(d.rms, 0.1 * 0.0008);
  EXPECT_LT(d.worst, 0.2 * 0.0008);
}

// A lean the relief cannot hold is lost, and said so, naming the object.
TEST(ObjectTexture, ALeaningNormalMapIsWarnedAboutNamingTheObject) {
  const thx::test::TempDir files("thx_object_tex");
  tex::TextureMap leaning(16, 16, tex::Representation::Normal);
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) leaning.setNormal(i, j, Eigen::Vector3f(-0.1f, 0.0f, 1.0f).normalized());
  const std::string file = files.file("leaning.png");
  tex::saveTexture(file, leaning);
  tex::LoadReport report;
  EXPECT_TRUE(objectTextureFrom(file, report).isRelief());
  ASSERT_EQ(report.warnings.size(), 1u);
  const std::string& w = report.warnings[0];
  EXPECT_NE(w.find("object 'block': its normal map leans on average (mean slope 0.1000"), std::string::npos) << w;
  EXPECT_NE(w.find("that lean is lost"), std::string::npos) << w;
}

TEST(ObjectTexture, AnUnreadableFileIsAnErrorNamingTheObject) {
  const thx::test::TempDir files("thx_object_tex");
  const std::string file = files.file("not_a.png");
  std::FILE* f = std::fopen(file.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fputs("not a PNG", f);
  std::fclose(f);
  const Scene scene = parse(boxWithFile(file));
  try {
    buildObjectTexture(scene, 0);
    FAIL() << "a missing file was accepted";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.field(), "objects[0].texture");
    EXPECT_NE(what.find("object 'block'"), std::string::npos) << what;
    EXPECT_NE(what.find("not_a.png"), std::string::npos) << what;
    EXPECT_NE(what.find("relief map"), std::string::npos) << what;
  }
}

}  // namespace

}  // namespace test_object_texture
