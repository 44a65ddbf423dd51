// The user studies' shipped surfaces (scenes/study/): both manifests keep their format (the trial
// runner reads exactly it), every entry names a scene the real loader accepts without warnings,
// the families have the paper's sizes, Study 2's relief and normal scenes share one texture, and
// names are unique tokens.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <map>
#include <set>
#include <tuple>

#include "scenes/scene_loader.hpp"
#include "scenes/scene_lookup.hpp"
#include "scenes/surface_texture.hpp"

namespace test_study_scenes {

namespace {

using namespace thx::scene;
namespace fs = std::filesystem;

const std::string kStudy = std::string(THX_SOURCE_DIR) + "/scenes/study/";

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += l + "\n";
  return s;
}

// Every key of `node` is one of `keys`, and each of them is there as a scalar.
void expectExactKeys(const YAML::Node& node, const std::set<std::string>& keys, const std::string& where) {
  ASSERT_TRUE(node.IsMap()) << where;
  for (const auto& kv : node) EXPECT_EQ(keys.count(kv.first.as<std::string>()), 1u) << where << ": " << kv.first;
  for (const std::string& k : keys) {
    ASSERT_TRUE(node[k]) << where << ": missing " << k;
    EXPECT_TRUE(node[k].IsScalar()) << where << ": " << k;
  }
}

// Loads a study scene: no warnings, a generated texture whose parameters generate() accepts (at
// 32² here: the generators' tests build the full sizes), one ball.
Scene loadStudyScene(const std::string& file) {
  EXPECT_TRUE(isValidSceneName(fs::path(file).stem().string())) << file;
  const Scene scene = loadScene(kStudy + file);
  EXPECT_TRUE(scene.warnings.empty()) << file << ":\n" << joined(scene.warnings);
  EXPECT_EQ(scene.surface.texture.kind, TextureSource::Kind::Generator) << file;
  EXPECT_EQ(scene.surface.texture.generator.size, 512) << file;  // the paper's texture size
  EXPECT_EQ(scene.surface.texture.generator.params.at("extent"), scene.surface.size_m.x()) << file;
  Scene small = scene;
  small.surface.texture.generator.size = 32;
  EXPECT_EQ(buildSurfaceTexture(small).width(), 32) << file;
  EXPECT_EQ(scene.objects.size(), 1u) << file;
  if (!scene.objects.empty()) {
    EXPECT_EQ(scene.objects[0].shape, Shape::Sphere) << file;
  }
  return scene;
}

// What makes a surface's texture and sound: generator, its parameters and seed, and the material.
auto surfaceKey(const Scene& s) {
  const auto& g = s.surface.texture.generator;
  return std::make_tuple(g.kind, g.params, g.seed, s.surface.material.name);
}

TEST(StudyScenes, IdentificationManifestNamesTenLoadableSurfacesInFourFamilies) {
  const YAML::Node m = YAML::LoadFile(kStudy + "identification.yaml");
  ASSERT_TRUE(m.IsMap());
  EXPECT_EQ(m.size(), 3u);
  EXPECT_EQ(m["study"].as<std::string>(), "identification");
  const Scene training = loadStudyScene(m["training"].as<std::string>());

  const YAML::Node surfaces = m["surfaces"];
  ASSERT_TRUE(surfaces.IsSequence());
  std::map<std::string, int> families;
  std::set<std::string> names, files;
  std::set<decltype(surfaceKey(training))> keys{surfaceKey(training)};
  for (const YAML::Node& e : surfaces) {
    expectExactKeys(e, {"name", "family", "scene"}, "identification.yaml");
    const std::string name = e["name"].as<std::string>(), file = e["scene"].as<std::string>();
    EXPECT_TRUE(isValidSceneName(name)) << name;
    EXPECT_TRUE(names.insert(name).second) << "duplicate name " << name;
    EXPECT_TRUE(files.insert(file).second) << "duplicate scene " << file;
    ++families[e["family"].as<std::string>()];
    const Scene s = loadStudyScene(file);
    // Study 1 presents the look separately; the surface everyone feels and hears is the normal map.
    EXPECT_EQ(s.surface.representation, thx::tex::Representation::Normal) << file;
    EXPECT_TRUE(keys.insert(surfaceKey(s)).second) << file << " repeats another surface's texture and material";
  }
  EXPECT_EQ(names.size(), 10u);
  const std::map<std::string, int> expected{{"bricks", 3}, {"porcelain", 2}, {"metal", 3}, {"wood", 2}};
  EXPECT_EQ(families, expected);
}

TEST(StudyScenes, ReliefVsNormalPairsShareTheirTexture) {
  const YAML::Node m = YAML::LoadFile(kStudy + "relief_vs_normal.yaml");
  ASSERT_TRUE(m.IsMap());
  EXPECT_EQ(m.size(), 2u);
  EXPECT_EQ(m["study"].as<std::string>(), "relief-vs-normal");
  const YAML::Node surfaces = m["surfaces"];
  ASSERT_TRUE(surfaces.IsSequence());
  std::map<std::string, int> families;
  std::set<std::string> names, files;
  for (const YAML::Node& e : surfaces) {
    expectExactKeys(e, {"name", "family", "relief", "normal"}, "relief_vs_normal.yaml");
    const std::string name = e["name"].as<std::string>();
    EXPECT_TRUE(isValidSceneName(name)) << name;
    EXPECT_TRUE(names.insert(name).second) << "duplicate name " << name;
    ++families[e["family"].as<std::string>()];
    const std::string relief_file = e["relief"].as<std::string>(), normal_file = e["normal"].as<std::string>();
    EXPECT_TRUE(files.insert(relief_file).second) << relief_file;
    EXPECT_TRUE(files.insert(normal_file).second) << normal_file;
    const Scene relief = loadStudyScene(relief_file), normal = loadStudyScene(normal_file);
    EXPECT_EQ(relief.surface.representation, thx::tex::Representation::Relief) << relief_file;
    EXPECT_EQ(normal.surface.representation, thx::tex::Representation::Normal) << normal_file;
    // One texture, one material, one ball: only the representation differs.
    const auto& gr = relief.surface.texture.generator;
    const auto& gn = normal.surface.texture.generator;
    EXPECT_EQ(gr.kind, gn.kind) << name;
    EXPECT_EQ(gr.size, gn.size) << name;
    EXPECT_EQ(gr.seed, gn.seed) << name;
    EXPECT_EQ(gr.params, gn.params) << name;
    EXPECT_EQ(relief.surface.size_m, normal.surface.size_m) << name;
    EXPECT_EQ(relief.surface.material.name, normal.surface.material.name) << name;
    ASSERT_EQ(relief.objects.size(), normal.objects.size()) << name;
    EXPECT_EQ(relief.objects[0].radius_m, normal.objects[0].radius_m) << name;
    EXPECT_EQ(relief.objects[0].mass_kg, normal.objects[0].mass_kg) << name;
  }
  EXPECT_EQ(names.size(), 6u);
  const std::map<std::string, int> expected{{"wood", 2}, {"stone", 2}, {"ceramic", 1}, {"metal", 1}};
  EXPECT_EQ(families, expected);
}

// hapticd and its clients find a scene by its file stem in one folder (--scenes-dir); the study
// scenes must not shadow the top-level ones, and every scene in the folder is in a manifest.
TEST(StudyScenes, SceneNamesAreUniqueAndAllListed) {
  std::set<std::string> top, study;
  for (const auto& e : fs::directory_iterator(std::string(THX_SOURCE_DIR) + "/scenes/"))
    if (e.path().extension() == ".yaml") top.insert(e.path().stem().string());
  for (const auto& e : fs::directory_iterator(kStudy))
    if (e.path().extension() == ".yaml" && e.path().stem().string().rfind("study", 0) == 0)  // not the manifests
      study.insert(e.path().filename().string());
  for (const std::string& f : study) EXPECT_EQ(top.count(fs::path(f).stem().string()), 0u) << f;

  std::set<std::string> listed;
  const YAML::Node id = YAML::LoadFile(kStudy + "identification.yaml");
  listed.insert(id["training"].as<std::string>());
  for (const YAML::Node& e : id["surfaces"]) listed.insert(e["scene"].as<std::string>());
  for (const YAML::Node& e : YAML::LoadFile(kStudy + "relief_vs_normal.yaml")["surfaces"]) {
    listed.insert(e["relief"].as<std::string>());
    listed.insert(e["normal"].as<std::string>());
  }
  EXPECT_EQ(study, listed);
  EXPECT_EQ(listed.size(), 11u + 12u);
}

}  // namespace

}  // namespace test_study_scenes
