// objects[].texture (issue 29): a relief map on a box's faces, parsed with the surface texture's
// rules, its tile defaulted from the generator's extent or the box, built by buildObjectTexture;
// misplaced or unusable textures are errors naming the object.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "scenes/scene_loader.hpp"
#include "scenes/surface_texture.hpp"
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

TEST(ObjectTexture, OnlyABoxCarriesATexture) {
  expectError(withObject("{name: ball, shape: sphere, radius: 0.01, mass: 0.05, position: [0, 0, 0.01],\n"
                         "     texture: {generator: grooves}}"),
              "objects[0].texture", {"only a box carries a texture", "no texture on a sphere"});
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

TEST(ObjectTexture, ANormalMapFileIsRefusedNamingTheObject) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("thx_object_tex_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  tex::GenerateRequest request;
  request.kind = "grooves";
  request.size = 16;
  const tex::TextureMap relief = tex::generate(request);
  tex::TextureMap normals(relief.width(), relief.height(), tex::Representation::Normal);
  for (int j = 0; j < relief.height(); ++j)
    for (int i = 0; i < relief.width(); ++i) normals.setNormal(i, j, relief.normal(i, j));
  const std::string file = (dir / "normals.png").string();
  tex::saveTexture(file, normals);
  const Scene scene =
      parse(withObject("{name: block, shape: box, size: [0.04, 0.03, 0.01], mass: 0.05, position: [0, 0, 0.005],\n"
                       "     texture: {file: " + file + "}}"));
  try {
    buildObjectTexture(scene, 0);
    FAIL() << "a normal map was accepted on a box";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.field(), "objects[0].texture");
    EXPECT_NE(what.find("object 'block'"), std::string::npos) << what;
    EXPECT_NE(what.find("relief map"), std::string::npos) << what;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace

}  // namespace test_object_texture
