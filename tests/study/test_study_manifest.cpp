// The study manifest (docs/study.md §5.1): the test manifests load; every rule's breach is
// refused with file, line and field.
#include <gtest/gtest.h>

#include <fstream>

#include "clients/study/study_manifest.hpp"
#include "tests/support/temp_dir.hpp"

namespace thx::study::test_study_manifest {
namespace {

const std::string kData = THX_TEST_DATA_DIR "/study";

TEST(StudyManifest, IdentificationLoads) {
  const StudyManifest m = loadManifest(kData + "/identification/manifest.yaml");
  EXPECT_EQ(m.study, Study::Identification);
  ASSERT_EQ(m.surfaces.size(), 5u);
  EXPECT_EQ(m.surfaces[0].name, "bricks_large");
  EXPECT_EQ(m.surfaces[0].family, "bricks");
  EXPECT_EQ(m.surfaces[0].scene, kData + "/identification/bricks_large.yaml");
  ASSERT_TRUE(m.training);
  EXPECT_EQ(sceneNameOf(*m.training), "training");
  EXPECT_EQ(m.candidates()[4], (Candidate{"porcelain_dimples", "porcelain"}));
}

TEST(StudyManifest, ReliefVsNormalLoads) {
  const StudyManifest m = loadManifest(kData + "/relief_vs_normal/manifest.yaml");
  EXPECT_EQ(m.study, Study::ReliefVsNormal);
  ASSERT_EQ(m.surfaces.size(), 4u);
  EXPECT_EQ(sceneNameOf(m.surfaces[2].relief), "tile_relief");
  EXPECT_EQ(sceneNameOf(m.surfaces[2].normal), "tile_normal");
  EXPECT_FALSE(m.training);
}

// Writes `text` as a manifest beside a scene file a.yaml and b.yaml; returns loadManifest's error.
std::string errorOf(const std::string& text) {
  test::TempDir dir("study_manifest");
  for (const char* f : {"a.yaml", "b.yaml", "c.yaml", "d.yaml"}) std::ofstream(dir.file(f)) << "version: 1\n";
  const std::string path = dir.file("m.yaml");
  std::ofstream(path) << text;
  try {
    loadManifest(path);
  } catch (const SessionError& e) {
    std::string w = e.what();
    return w.substr(w.find("m.yaml"));
  }
  return "no error";
}

TEST(StudyManifest, BadInputNamesFileLineAndField) {
  const std::string ok1 = "study: identification\ntraining: a.yaml\nsurfaces:\n";
  EXPECT_EQ(errorOf("study: taste\n"), "m.yaml:1: study: expected identification or relief-vs-normal, got 'taste'");
  EXPECT_EQ(errorOf("surfaces: []\n"), "m.yaml:1: study: missing; expected a value");
  EXPECT_EQ(errorOf(ok1 + "  - {name: x, family: f, scene: a.yaml}\n  - {name: y, family: tile wall, scene: b.yaml}\n"),
            "m.yaml:5: surfaces[1].family: expected a name of letters, digits and _-.+, got 'tile wall'");
  EXPECT_EQ(errorOf(ok1 + "  - {name: x, family: f, scene: a.yaml}\n  - {name: x, family: f, scene: b.yaml}\n"),
            "m.yaml:5: surfaces[1].name: 'x' is named twice; expected unique names");
  EXPECT_EQ(errorOf(ok1 + "  - {name: x, family: f, scene: a.yaml}\n  - {name: y, family: f, scene: nosuch.yaml}\n").substr(0, 40),
            "m.yaml:5: surfaces[1].scene: no such fil");
  EXPECT_EQ(errorOf(ok1 + "  - {name: x, family: f, scene: ../a.yaml}\n  - {name: y, family: f, scene: b.yaml}\n"),
            "m.yaml:4: surfaces[0].scene: expected a file name NAME.yaml in the manifest's folder (hapticd switches "
            "scenes by name within one folder), got '../a.yaml'");
  EXPECT_EQ(errorOf(ok1 + "  - {name: x, family: f, scene: a.yaml, look: b.yaml}\n"),
            "m.yaml:4: surfaces[0].look: unknown field; expected one of family, name, scene");
  EXPECT_EQ(errorOf(ok1 + "  - {name: x, family: f, scene: a.yaml}\n"),
            "m.yaml:4: surfaces: expected at least 2 candidates, got 1");
  EXPECT_EQ(errorOf("study: identification\nsurfaces: []\n"), "m.yaml:1: training: missing; expected a value");
  EXPECT_EQ(errorOf("study: relief-vs-normal\ntraining: a.yaml\nsurfaces: []\n"),
            "m.yaml:2: training: unknown field; expected one of study, surfaces");
  EXPECT_EQ(errorOf("study: relief-vs-normal\nsurfaces:\n  - {name: x, family: f, relief: a.yaml, normal: b.yaml}\n"),
            "m.yaml:3: surfaces: expected an even number (at least 2) so half can be relief and half normal, got 1");
  EXPECT_EQ(errorOf("study: relief-vs-normal\nsurfaces:\n  - {name: x, family: f, relief: a.yaml}\n"),
            "m.yaml:3: surfaces[0].normal: missing; expected a value");
  EXPECT_EQ(errorOf("study: [1]\n"), "m.yaml:1: study: expected a plain value, got a sequence");
  EXPECT_EQ(errorOf("study: identification\n  bad: [\n").substr(0, 22), "m.yaml:2: not valid YA");
}

TEST(StudyManifest, MissingFileIsNamed) {
  try {
    loadManifest("/nonexistent/m.yaml");
    FAIL();
  } catch (const SessionError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/m.yaml: cannot read the manifest");
  }
}

}  // namespace
}  // namespace thx::study::test_study_manifest
