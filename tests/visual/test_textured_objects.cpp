// Textured objects (issue 29): a box whose faces carry a relief map, and a ball with a bump map,
// drawn with the textured mesh's shaders on the mesh the physics' layout describes
// (meshes/textured_box_mesh.hpp, meshes/textured_ball_mesh.hpp): against the CPU reference in
// normal and relief mode, and in a scene's frame at the body's pose, the box's faces shaded by the
// texture where the plain box's are flat, and a scene's textured ball drawn textured.
#include "tests/visual/mesh_fixture.hpp"

#include "clients/visual/scene_objects.hpp"
#include "clients/visual/textured_object_renderer.hpp"
#include "meshes/textured_ball_mesh.hpp"
#include "meshes/textured_box_mesh.hpp"
#include "scenes/scene_loader.hpp"

namespace thx::visual::testing::test_textured_objects {
namespace {

constexpr double kTile = 0.016;

// A textured object's mesh with its texture, as TexturedObjectRenderer lays it.
MeshSurface objectSurface(const mesh::TexturedMesh& m, double tile, const tex::TextureMap& map, bool relief) {
  MeshSurface s;
  s.mesh = &m;
  s.tile_m = Eigen::Vector2d::Constant(tile);
  s.map = &map;
  s.use_relief = relief;
  return s;
}

struct TexturedBox {
  mesh::TexturedMesh box = mesh::texturedBoxMesh({0.03, 0.024, 0.012}, kTile);
  tex::TextureMap map = tex::generate({"bricks", 128, {{"extent", kTile}}, 5});
  MeshSurface surface(bool relief) const { return objectSurface(box, kTile, map, relief); }
};

TEST(VisualTexturedObjects, ANormalMappedBoxMatchesItsReference) {
  const TexturedBox t;
  const RenderSettings settings = referenceLighting(SurfaceMode::Normal);
  // Three faces in view, two of them mirrored charts (handedness -1).
  for (const double azimuth : {-60.0, 120.0}) {
    const MeshComparison c = meshAgainstReference("normal-mapped box", t.surface(false), settings,
                                                  orbitCamera(35, azimuth, 0.07, Eigen::Vector3d::Zero()));
    EXPECT_GT(c.stats.compared, kImageSide * kImageSide / 5);
    EXPECT_LE(c.stats.meanError(), 1.0);
    EXPECT_LE(c.stats.max_error, 4);
  }
}

TEST(VisualTexturedObjects, AReliefBoxMatchesItsReference) {
  const TexturedBox t;
  RenderSettings settings = referenceLighting(SurfaceMode::Relief);
  settings.steps = {16, 6, 0};
  const MeshComparison c = meshAgainstReference("relief box", t.surface(true), settings,
                                                orbitCamera(35, -60, 0.07, Eigen::Vector3d::Zero()));
  EXPECT_GT(c.stats.compared, kImageSide * kImageSide / 5);
  EXPECT_LE(c.stats.otherTexelFraction(), 0.01);
  EXPECT_LE(c.stats.meanError(), 0.5);
  EXPECT_LE(c.mean_depth_error_m, finalInterval(t.map, settings.steps));
}

// A 1.2 cm ball, one tile per face of its cube (pi r / 2 = 18.8 mm), dimples four to a
// face each way.
struct TexturedBall {
  double tile = mesh::ballFaceArc(0.012);
  mesh::TexturedMesh ball = mesh::texturedBallMesh(0.012, tile, 24);
  tex::TextureMap map = tex::generate({"dimples", 128, {{"extent", tile}, {"spacing", tile / 4}, {"radius", tile / 10},
                                                        {"depth", 0.0004}}, 1});
  MeshSurface surface(bool relief) const { return objectSurface(ball, tile, map, relief); }
};

TEST(VisualTexturedObjects, ABumpMappedBallMatchesItsReference) {
  const TexturedBall t;
  // A cube corner in view (three faces, mirrored charts among them) and a face's centre.
  for (const double elevation : {35.0, 89.0}) {
    const RenderSettings settings = referenceLighting(SurfaceMode::Normal);
    const MeshComparison c = meshAgainstReference("normal-mapped ball", t.surface(false), settings,
                                                  orbitCamera(elevation, -45, 0.045, Eigen::Vector3d::Zero()));
    EXPECT_GT(c.stats.compared, kImageSide * kImageSide / 5);
    EXPECT_LE(c.stats.meanError(), 1.0);
    EXPECT_LE(c.stats.max_error, 4);
  }
  RenderSettings settings = referenceLighting(SurfaceMode::Relief);
  settings.steps = {16, 6, 0};
  const MeshComparison c = meshAgainstReference("relief ball", t.surface(true), settings,
                                                orbitCamera(35, -45, 0.045, Eigen::Vector3d::Zero()));
  EXPECT_GT(c.stats.compared, kImageSide * kImageSide / 5);
  EXPECT_LE(c.stats.otherTexelFraction(), 0.01);
  EXPECT_LE(c.stats.meanError(), 0.5);
}

// A scene's objects drawn on the sine plane from `elevation_deg` at 8 cm, plain and with the
// scene's textured objects.
struct PlainAndTextured {
  Camera camera;
  Rgba8Image plain, textured;
};
PlainAndTextured drawPlainAndTextured(const scene::Scene& scene, const std::vector<ObjectInstance>& objects,
                                      double elevation_deg) {
  const OwnedSurface s = generated("sine", 32, {});
  const RenderSettings settings = referenceLighting(SurfaceMode::Normal);
  context();
  CameraPlacement placement;
  placement.elevation_deg = elevation_deg;
  placement.azimuth_deg = -90;
  placement.distance_m = 0.08;
  const Camera camera(placement, s.surface.mapping().plane_to_world, kImageSide, kImageSide);
  FrameRenderer plain(s.surface, settings, kImageSide, kImageSide);
  plain.render(camera, objects);
  FrameRenderer textured(s.surface, settings, kImageSide, kImageSide);
  textured.setTexturedObjects(scene);
  textured.render(camera, objects);
  return {camera, plain.framebuffer().readColour(), textured.framebuffer().readColour()};
}

TEST(VisualTexturedObjects, ASceneBallWithATextureIsDrawnTextured) {
  const scene::Scene scene = scene::parseScene(
      "version: 1\nname: t\nsurface:\n  size: [0.1, 0.1]\n  texture: {generator: sine, size: 32}\n"
      "objects:\n  - {name: ball, shape: sphere, radius: 0.012, mass: 0.05, position: [0, 0, 0.012],\n"
      "     texture: {generator: dimples, size: 128, params: {spacing: 0.00471239, radius: 0.0015, depth: 0.0004}}}\n",
      "t.yaml", "");
  const std::vector<ObjectInstance> objects = objectsAtRest(scene);
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_EQ(objects[0].textured_object, 0);
  const PlainAndTextured frames = drawPlainAndTextured(scene, objects, 60);
  // The ball's pixels differ (its dimples), the plane's corners do not.
  const Rgba8Image &a = frames.plain, &b = frames.textured;
  int differ = 0;
  for (int y = 0; y < kImageSide; ++y)
    for (int x = 0; x < kImageSide; ++x) differ += std::abs(int(a.at(x, y, 0)) - int(b.at(x, y, 0))) > 8;
  EXPECT_GT(differ, 200);
  EXPECT_EQ(a.at(2, 2, 0), b.at(2, 2, 0));
  EXPECT_EQ(a.at(kImageSide - 3, kImageSide - 3, 1), b.at(kImageSide - 3, kImageSide - 3, 1));
}

// The spread of the red channel over the box's top face, seen from above.
double topFaceSpread(const Rgba8Image& image, const Camera& camera, const Eigen::Isometry3d& pose,
                     const Eigen::Vector3d& half) {
  double sum = 0, sum2 = 0;
  int n = 0;
  for (double s = -0.8; s <= 0.8; s += 0.05)
    for (double t = -0.8; t <= 0.8; t += 0.05) {
      const Eigen::Vector3d p = pose * Eigen::Vector3d(s * half.x(), t * half.y(), half.z());
      const Eigen::Vector4d clip = camera.viewProjection() * p.homogeneous();
      const int x = int((clip.x() / clip.w() + 1) / 2 * kImageSide), y = int((1 - clip.y() / clip.w()) / 2 * kImageSide);
      if (x < 0 || x >= kImageSide || y < 0 || y >= kImageSide) continue;
      const double red = image.at(x, y, 0);
      sum += red, sum2 += red * red, ++n;
    }
  EXPECT_GT(n, 500);
  return std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)));
}

TEST(VisualTexturedObjects, ASceneBoxIsDrawnTexturedAtItsPose) {
  const scene::Scene scene = scene::parseScene(
      "version: 1\nname: t\nsurface:\n  size: [0.1, 0.1]\n  texture: {generator: sine, size: 32}\n"
      "objects:\n  - {name: block, shape: box, size: [0.03, 0.024, 0.012], mass: 0.05, position: [0, 0, 0.006],\n"
      "     texture: {generator: bricks, size: 128, seed: 5}, texture_tile: 0.016}\n",
      "t.yaml", "");
  // Moved and turned from the scene's pose, as physics_poses_t would place it.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(Eigen::Vector3d(0.004, -0.003, 0.006));
  pose.rotate(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()));
  const std::vector<ObjectInstance> objects = objectsAt(scene, {pose});
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_EQ(objects[0].textured_object, 0);
  EXPECT_TRUE(untexturedObjects(objects).empty());

  const PlainAndTextured frames = drawPlainAndTextured(scene, objects, 85);
  const Eigen::Vector3d half(0.015, 0.012, 0.006);
  const double plain_spread = topFaceSpread(frames.plain, frames.camera, pose, half);
  const double textured_spread = topFaceSpread(frames.textured, frames.camera, pose, half);
  std::printf("top face red spread: plain %.2f, textured %.2f\n", plain_spread, textured_spread);
  EXPECT_LT(plain_spread, 2.0);       // one flat face under one light
  EXPECT_GT(textured_spread, 10.0);   // the bricks' mortar and faces
  // Outside the box's footprint both frames show the same plane.
  const Rgba8Image &a = frames.plain, &b = frames.textured;
  EXPECT_EQ(a.at(2, 2, 0), b.at(2, 2, 0));
  EXPECT_EQ(a.at(kImageSide - 3, kImageSide - 3, 1), b.at(kImageSide - 3, kImageSide - 3, 1));
}

}  // namespace
}  // namespace thx::visual::testing::test_textured_objects
