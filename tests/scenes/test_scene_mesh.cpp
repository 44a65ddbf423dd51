// surface.mesh: the surface as a textured triangle mesh (docs/scenes.md, "surface.mesh"). The
// loader reads and checks the section; buildSceneMesh builds the mesh every program shares; the
// programs that simulate or hear the plane only refuse a mesh scene by name.
#include <gtest/gtest.h>

#include "scenes/scene_loader.hpp"
#include "scenes/scene_mesh.hpp"

namespace test_scene_mesh {

namespace {

using namespace thx::scene;

const std::string kMeshDir = std::string(THX_TEST_DATA_DIR) + "/meshes";

std::string sceneWith(const std::string& mesh, const std::string& rest = "", const std::string& size = "[0.04, 0.04]") {
  return "version: 1\nname: m\nsurface:\n  size: " + size +
         "\n  texture: {generator: bricks, size: 16, params: {extent: 0.04}}\n  mesh: " + mesh + "\n" + rest;
}

Scene parse(const std::string& text) { return parseScene(text, "m.yaml", kMeshDir); }

// The error's field and every part of its message.
void expectError(const std::string& text, const std::string& field, const std::vector<std::string>& parts) {
  try {
    parse(text);
    FAIL() << "no error for:\n" << text;
  } catch (const SceneError& e) {
    EXPECT_EQ(e.field(), field) << e.what();
    for (const std::string& part : parts)
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << "'" << part << "' not in: " << e.what();
  }
}

TEST(SceneMesh, GeneratorWithItsDefaults) {
  const Scene s = parse(sceneWith("{generator: bowl, size: 0.06}"));
  ASSERT_TRUE(s.surface.mesh.has_value());
  const MeshSource& m = *s.surface.mesh;
  EXPECT_EQ(m.kind, MeshSource::Kind::Generator);
  EXPECT_EQ(m.generator, "bowl");
  EXPECT_DOUBLE_EQ(m.size_m, 0.06);
  EXPECT_EQ(m.segments, 128);
  EXPECT_EQ(m.max_triangles, 1'000'000u);
  EXPECT_FALSE(m.closed);
  EXPECT_EQ(m.where.line, 6);
  EXPECT_TRUE(s.warnings.empty());
}

TEST(SceneMesh, FileResolvedAgainstTheSceneWithUnitAndProjection) {
  const Scene s = parse(sceneWith("{file: cube.obj, unit: 0.01, projection: cylindrical, max_triangles: 12, closed: true}"));
  const MeshSource& m = *s.surface.mesh;
  EXPECT_EQ(m.kind, MeshSource::Kind::File);
  EXPECT_EQ(m.file, kMeshDir + "/cube.obj");
  EXPECT_DOUBLE_EQ(m.unit_m, 0.01);
  EXPECT_EQ(m.projection, MeshProjection::Cylindrical);
  EXPECT_EQ(m.max_triangles, 12u);
  EXPECT_TRUE(m.closed);
}

TEST(SceneMesh, PlaneScenesHaveNone) {
  EXPECT_FALSE(parse("version: 1\nname: p\nsurface: {size: [0.2, 0.2], texture: {generator: bricks, size: 16}}\n")
                   .surface.mesh.has_value());
}

TEST(SceneMesh, BadSections) {
  expectError(sceneWith("{generator: bowl, size: 0.06, file: cube.obj}"), "surface.mesh", {"both file and generator"});
  expectError(sceneWith("{size: 0.06}"), "surface.mesh", {"no mesh source", "{generator: SHAPE, size: m} or {file: PATH}"});
  expectError(sceneWith("{generator: bwol, size: 0.06}"), "surface.mesh.generator",
              {"did you mean 'bowl'?", "sphere, cylinder, torus, bowl, vase, box, room, plate", "got 'bwol'"});
  expectError(sceneWith("{generator: bowl}"), "surface.mesh.size", {"missing required field"});
  expectError(sceneWith("{generator: bowl, size: 0.06, unit: 0.001}"), "surface.mesh.unit", {"only to mesh files"});
  expectError(sceneWith("{file: cube.obj, segments: 64}"), "surface.mesh.segments", {"only to generated meshes"});
  expectError(sceneWith("{generator: bowl, size: 0.06, segments: 4}"), "surface.mesh.segments", {"out of range"});
  expectError(sceneWith("{generator: bowl, size: 2}"), "surface.mesh.size", {"out of range"});
  expectError(sceneWith("{file: no_such.obj}"), "surface.mesh.file", {"no_such.obj"});
  expectError(sceneWith("{file: cube.obj, projection: conical}"), "surface.mesh.projection",
              {"one of: none, planar, cylindrical, spherical"});
  expectError(sceneWith("{file: cube.obj, max_triangles: 0}"), "surface.mesh.max_triangles", {"out of range"});
  expectError(sceneWith("{generator: bowl, size: 0.06}", "", "[0.04, 0.02]"), "surface.mesh.generator",
              {"tiles the texture in squares", "got [0.04, 0.02]"});
  expectError(sceneWith("{generator: sphere, size: 0.05, colour: red}"), "surface.mesh.colour", {"unknown field"});
}

TEST(SceneMesh, ObjectsOnAMeshSurfaceParseBelowItsFramesPlaneWithoutAWarning) {
  // A marble in a bowl sits below the surface frame's z = 0 (the bowl's rim is above it).
  const Scene s = parse(sceneWith("{generator: bowl, size: 0.06}",
                                  "objects:\n  - {name: b, shape: sphere, radius: 0.01, mass: 0.01, position: [0, 0, -0.01]}\n"));
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].name, "b");
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

// On a mesh the script's points are in the mesh's frame, not on the texture's rectangle.
TEST(SceneMesh, ScriptPointsBeyondOneTextureTile) {
  const Scene s = parse(sceneWith("{generator: bowl, size: 0.06}",
                                  "device:\n  script:\n    - stroke: {from: [-0.05, 0], to: [0.05, 0], speed: 0.04, force: 1}\n"));
  EXPECT_EQ(s.device.script.size(), 1u);
  expectError("version: 1\nname: p\nsurface: {size: [0.04, 0.04], texture: {generator: bricks, size: 16}}\n"
              "device:\n  script:\n    - stroke: {from: [-0.05, 0], to: [0.05, 0], speed: 0.04, force: 1}\n",
              "device.script[0].stroke.from", {"outside the surface"});
}

TEST(SceneMesh, BuildsTheGeneratedShapeOnTheScenesTile) {
  const Scene s = parse(sceneWith("{generator: sphere, size: 0.05, segments: 32, closed: true}",
                                  "", "[0.04, 0.04]") );
  const SceneMesh m = buildSceneMesh(s);
  EXPECT_EQ(m.mesh.triangles.size(), std::size_t(2 * 32 * (16 - 1)));  // two pole fans of 32, 14 rings of quads
  EXPECT_TRUE(m.mesh.hasFrames());
  // 2 pi 0.05 / 0.04 = 7.85 tiles around, rounded to 8.
  EXPECT_NEAR(m.tile_m.x(), 2 * 3.141592653589793 * 0.05 / 8, 1e-12);
  EXPECT_TRUE(m.mesh_to_world.isApprox(Eigen::Isometry3d::Identity()));
}

// hello_t's fingerprint of a mesh scene: the texture's hashed with the mesh, so two hosts whose
// meshes differ (a file edited on one, another tessellation, another pose) do not agree.
TEST(SceneMesh, TheFingerprintFollowsTheMeshItsPoseAndTheTexture) {
  const SceneMesh a = buildSceneMesh(parse(sceneWith("{generator: sphere, size: 0.05, segments: 32}")));
  const std::uint64_t texture = 0x0123456789abcdefULL;
  const std::uint64_t fp = meshSceneFingerprint(texture, a);
  EXPECT_EQ(meshSceneFingerprint(texture, buildSceneMesh(parse(sceneWith("{generator: sphere, size: 0.05, segments: 32}")))), fp);
  EXPECT_NE(fp, texture);
  EXPECT_NE(meshSceneFingerprint(texture + 1, a), fp);
  EXPECT_NE(meshSceneFingerprint(texture, buildSceneMesh(parse(sceneWith("{generator: sphere, size: 0.05, segments: 36}")))), fp);
  EXPECT_NE(meshSceneFingerprint(texture, buildSceneMesh(parse(sceneWith(
                                              "{generator: sphere, size: 0.05, segments: 32, pose: {position: [0, 0, 0.001]}}")))),
            fp);
  SceneMesh moved_uv = a;
  moved_uv.mesh.uvs[7].x() += 1e-9;  // one texture coordinate, a nanometre's worth of a tile
  EXPECT_NE(meshSceneFingerprint(texture, moved_uv), fp);
}

TEST(SceneMesh, PosePlacesTheMesh) {
  const Scene s = parse(sceneWith("{generator: bowl, size: 0.06, segments: 16}",
                                  "", "[0.04, 0.04]\n  pose: {position: [0, 0, -0.04], rpy_deg: [0, 0, 90]}"));
  const SceneMesh m = buildSceneMesh(s);
  EXPECT_TRUE((m.mesh_to_world * Eigen::Vector3d(1, 0, 0)).isApprox(Eigen::Vector3d(0, 1, -0.04), 1e-12));
}

// The mesh's own pose places it in the surface frame, the surface's that frame in the world.
TEST(SceneMesh, TheMeshsPoseIsWithinTheSurfaceFrame) {
  const Scene s = parse(sceneWith("{generator: cylinder, size: 0.03, segments: 16, pose: {position: [-0.03, 0, 0], rpy_deg: [0, 90, 0]}}",
                                  "", "[0.04, 0.04]\n  pose: {position: [0, 0, -0.05]}"));
  const SceneMesh m = buildSceneMesh(s);
  // The tube's axis (its z) runs along the surface frame's x, from x = -0.03; the frame sits 5 cm down.
  EXPECT_TRUE((m.mesh_to_world.linear() * Eigen::Vector3d::UnitZ()).isApprox(Eigen::Vector3d::UnitX(), 1e-12));
  EXPECT_TRUE((m.mesh_to_world * Eigen::Vector3d::Zero()).isApprox(Eigen::Vector3d(-0.03, 0, -0.05), 1e-12));
}

TEST(SceneMesh, FileScaledByItsUnit) {
  const SceneMesh m = buildSceneMesh(parse(sceneWith("{file: cube.obj, unit: 0.01, closed: true}")));
  EXPECT_EQ(m.mesh.triangles.size(), 12u);
  for (const Eigen::Vector3d& p : m.mesh.positions) EXPECT_NEAR(p.cwiseAbs().maxCoeff(), 0.01, 1e-12);
  EXPECT_EQ(m.tile_m, Eigen::Vector2d(0.04, 0.04));
}

// The mesh's own errors name the scene's line and the mesh's problem.
TEST(SceneMesh, MeshErrorsAreLocatedAtTheMeshField) {
  try {
    buildSceneMesh(parse(sceneWith("{generator: bowl, size: 0.06, segments: 16, max_triangles: 100}")));
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.field(), "surface.mesh");
    EXPECT_EQ(e.where().line, 6);
    EXPECT_NE(std::string(e.what()).find("more than the limit of 100"), std::string::npos) << e.what();
  }
  try {
    buildSceneMesh(parse(sceneWith("{file: flipped_face.obj}")));
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.field(), "surface.mesh");
    EXPECT_NE(std::string(e.what()).find("flipped_face.obj"), std::string::npos) << e.what();
  }
}

TEST(SceneMesh, PlaneOnlyProgramsRefuseAMeshByName) {
  const Scene s = parse(sceneWith("{generator: bowl, size: 0.06}"));
  try {
    requirePlaneSurface(s, "audio-client");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.field(), "surface.mesh");
    EXPECT_NE(std::string(e.what()).find("m.yaml:6:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("audio-client"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("hapticd"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(requirePlaneSurface(parse("version: 1\nname: p\nsurface: {size: [0.2, 0.2], texture: {generator: bricks, size: 16}}\n"),
                                      "audio-client"));
}

}  // namespace

}  // namespace test_scene_mesh
