// buildSurfaceTexture: the scene's texture options reach generate()/loadTexture(), and texture
// errors come back as SceneErrors located at the scene's `texture:` line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "scenes/scene_loader.hpp"
#include "scenes/surface_texture.hpp"
#include "textures/generators.hpp"
#include "textures/smoothing.hpp"
#include "textures/texture_io.hpp"

namespace test_surface_texture {

namespace {

using namespace thx::scene;
namespace tex = thx::tex;

std::string generated(const std::string& surface_extra, const std::string& params = "{extent: 0.1}") {
  return "version: 1\nname: t\nsurface:\n  size: [0.1, 0.1]\n  texture: {generator: bricks, size: 32, params: " +
         params + "}\n" + surface_extra;
}

class TempDir {
 public:
  TempDir() : path_(std::filesystem::temp_directory_path() / ("thx_scene_tex_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

TEST(SurfaceTexture, GeneratedReliefByDefault) {
  const tex::TextureMap map = buildSurfaceTexture(parseScene(generated(""), "t.yaml", ""));
  EXPECT_EQ(map.width(), 32);
  EXPECT_TRUE(map.isRelief());
  EXPECT_GT(map.maxDepth(), 0.0);
  EXPECT_DOUBLE_EQ(map.meta().extent_x_m, 0.1);
  EXPECT_EQ(map.meta().kind, "bricks");
}

TEST(SurfaceTexture, GeneratedAsNormalMapDropsDepth) {
  const tex::TextureMap relief = buildSurfaceTexture(parseScene(generated(""), "t.yaml", ""));
  const tex::TextureMap normal = buildSurfaceTexture(parseScene(generated("  representation: normal\n"), "t.yaml", ""));
  EXPECT_FALSE(normal.isRelief());
  EXPECT_EQ(normal.maxDepth(), 0.0);
  for (int j = 0; j < 32; j += 5)
    for (int i = 0; i < 32; i += 3) EXPECT_TRUE(normal.normal(i, j).isApprox(relief.normal(i, j), 1e-4f));
}

TEST(SurfaceTexture, MaxDepthOverrideRescalesGeneratedDepth) {
  const tex::TextureMap own = buildSurfaceTexture(parseScene(generated(""), "t.yaml", ""));
  const tex::TextureMap deeper = buildSurfaceTexture(parseScene(generated("  max_depth: 0.01\n"), "t.yaml", ""));
  EXPECT_DOUBLE_EQ(deeper.maxDepth(), 0.01);
  for (int j = 0; j < 32; j += 3)
    for (int i = 0; i < 32; i += 3) {
      EXPECT_EQ(deeper.depthCode(i, j), own.depthCode(i, j));
      EXPECT_NEAR(deeper.depth(i, j), own.depth(i, j) * 0.01 / own.maxDepth(), 1e-6);
    }
}

TEST(SurfaceTexture, MaxDepthAsAFractionOfTheSurfaceWidth) {
  // generated() makes a 0.1 m wide surface: 2 % of it is 2 mm.
  const Scene scene = parseScene(generated("  max_depth_fraction: 0.02\n"), "t.yaml", "");
  ASSERT_TRUE(scene.surface.max_depth_m.has_value());
  EXPECT_DOUBLE_EQ(*scene.surface.max_depth_m, 0.02 * scene.surface.size_m.x());
  EXPECT_DOUBLE_EQ(buildSurfaceTexture(scene).maxDepth(), 0.002);
  // The same depth given in metres builds the same texture.
  const Scene metres = parseScene(generated("  max_depth: 0.002\n"), "t.yaml", "");
  const tex::TextureMap a = buildSurfaceTexture(scene), b = buildSurfaceTexture(metres);
  EXPECT_EQ(a.maxDepth(), b.maxDepth());
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i) EXPECT_EQ(a.depthCode(i, j), b.depthCode(i, j));
}

TEST(SurfaceTexture, SmoothingUsesTheSmootherEveryProgramShares) {
  const Scene scene = parseScene(generated("  smoothing_sigma: 1.5\n"), "t.yaml", "");
  const Scene plain = parseScene(generated(""), "t.yaml", "");
  // Without a filter given, the built-in one (what hapticd uses) smooths: the texels change, and
  // exactly as tex::smoothTexture with the scene's sigma and address mode changes them.
  const tex::TextureMap by_default = buildSurfaceTexture(scene);
  const tex::TextureMap unsmoothed = buildSurfaceTexture(plain);
  tex::SmoothOptions o;
  o.sigma_texels = 1.5;
  o.address = scene.surface.sampling.address;
  const tex::TextureMap expected = tex::smoothTexture(unsmoothed, o);
  int changed = 0;
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i) {
      changed += by_default.normal(i, j) != unsmoothed.normal(i, j) ? 1 : 0;
      EXPECT_EQ(by_default.normal(i, j), expected.normal(i, j)) << i << "," << j;
    }
  EXPECT_GT(changed, 0);
  SurfaceTextureOptions options;
  double sigma_seen = 0.0;
  options.smooth = [&](const tex::TextureMap& map, const tex::SmoothOptions& so) {
    sigma_seen = so.sigma_texels;
    return tex::smoothTexture(map, so);
  };
  const tex::TextureMap smoothed = buildSurfaceTexture(scene, options);
  EXPECT_EQ(sigma_seen, 1.5);
  EXPECT_EQ(smoothed.width(), 32);
}

TEST(SurfaceTexture, FileTextureLoadsWithTheScenesOptions) {
  TempDir dir;
  tex::GenerateRequest request;
  request.kind = "bricks";
  request.size = 16;
  request.params = {{"extent", 0.1}};
  tex::saveTexture((dir.path() / "bricks.png").string(), tex::generate(request));
  std::ofstream(dir.path() / "scene.yaml")
      << "version: 1\nname: f\nsurface:\n  size: [0.1, 0.1]\n  texture: {file: bricks.png}\n  max_depth: 0.004\n";
  const Scene scene = loadScene((dir.path() / "scene.yaml").string());
  tex::LoadReport report;
  SurfaceTextureOptions options;
  options.report = &report;
  const tex::TextureMap map = buildSurfaceTexture(scene, options);
  EXPECT_EQ(map.width(), 16);
  EXPECT_TRUE(map.isRelief());
  EXPECT_DOUBLE_EQ(map.maxDepth(), 0.004);
  EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
}

TEST(SurfaceTexture, FileExtentDifferentFromSurfaceIsReported) {
  TempDir dir;
  tex::GenerateRequest request;
  request.kind = "bricks";
  request.size = 16;
  request.params = {{"extent", 0.3}};
  tex::saveTexture((dir.path() / "wide.png").string(), tex::generate(request));
  const Scene scene = parseScene("version: 1\nname: f\nsurface:\n  size: [0.1, 0.1]\n  texture: {file: wide.png}\n",
                                 "f.yaml", dir.path().string());
  tex::LoadReport report;
  SurfaceTextureOptions options;
  options.report = &report;
  buildSurfaceTexture(scene, options);
  ASSERT_FALSE(report.warnings.empty());
  EXPECT_NE(report.warnings.back().find("normals were computed for 0.3 x 0.3 m"), std::string::npos)
      << report.warnings.back();
}

TEST(SurfaceTexture, TextureErrorsComeBackLocatedInTheScene) {
  TempDir dir;
  std::ofstream(dir.path() / "broken.png") << "this is not a PNG";
  const Scene scene = parseScene("version: 1\nname: f\nsurface:\n  size: [0.1, 0.1]\n  texture: {file: broken.png}\n",
                                 "f.yaml", dir.path().string());
  try {
    buildSurfaceTexture(scene);
    FAIL() << "a broken PNG must not load";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.field(), "surface.texture");
    EXPECT_EQ(e.where().line, 5);
    EXPECT_NE(std::string(e.what()).find("broken.png"), std::string::npos) << e.what();
  }
}

}  // namespace

}  // namespace test_surface_texture
