// The bad-scene corpus: every file in tests/data/bad_scenes has exactly one problem, and its
// error must name the file, line, column, field path, value and expectation.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "scenes/scene_loader.hpp"

namespace test_bad_scenes {

namespace {

using thx::scene::SceneError;

struct BadScene {
  std::string file;
  int line;
  std::string field;                  // exact SceneError::field()
  std::vector<std::string> contains;  // substrings of what()
};

// gtest prints a parameter without a printer as its raw bytes, into every ctest line.
void PrintTo(const BadScene& s, std::ostream* os) { *os << s.file; }

const std::string kDir = std::string(THX_TEST_DATA_DIR) + "/bad_scenes/";

const std::vector<BadScene>& corpus() {
  static const std::vector<BadScene> cases = {
      {"syntax_unclosed_sequence.yaml", 6, "", {"syntax_unclosed_sequence.yaml:6:", "YAML syntax error", "sequence"}},
      {"tab_indentation.yaml", 5, "", {"tab_indentation.yaml:5:", "YAML syntax error", "tabs"}},
      {"empty.yaml", 1, "", {"empty.yaml:1:1", "empty scene", "version, name, surface"}},
      {"missing_version.yaml", 1, "version", {"missing_version.yaml:1:1", "version: missing required field"}},
      {"unsupported_version.yaml", 1, "version", {":1:10", "unsupported version", "expected 1", "got '2'"}},
      {"missing_texture.yaml", 3, "surface.texture", {":3:1", "missing required field", "{file: PATH}"}},
      {"unknown_field_typo.yaml",
       5,
       "surface.texure",
       {":5:3", "unknown field 'texure'", "did you mean 'texture'?", "one of: size, pose, texture"}},
      {"duplicate_key.yaml", 6, "name", {":6:1", "duplicate field", "first given on line 2"}},
      {"not_a_number.yaml", 4, "surface.size[1]", {":4:15", "wrong type", "expected a number", "got 'abc'"}},
      {"nan_stiffness.yaml", 8, "device.stiffness_fraction", {":8:23", "not a finite number", "got '.nan'", "[0, 1]"}},
      {"stiffness_out_of_range.yaml", 8, "device.stiffness_fraction", {":8:23", "out of range", "[0, 1]", "got '1.5'"}},
      {"wrong_sequence_length.yaml",
       11,
       "objects[0].position",
       {":11:15", "wrong length", "3 numbers [x, y, z]", "got a sequence of 2 items"}},
      {"surface_not_mapping.yaml", 3, "surface", {":3:10", "wrong type", "a mapping", "got a sequence of 2 items"}},
      {"unknown_representation.yaml",
       6,
       "surface.representation",
       {":6:19", "unknown value", "one of: normal, relief", "got 'bumpy'"}},
      {"unknown_material.yaml",
       6,
       "surface.material",
       {":6:13", "unknown material", "did you mean 'aluminium'?", "steel", "got 'aluminum'"}},
      {"unknown_device_model.yaml",
       8,
       "device.model",
       {":8:10", "unknown device model", "did you mean 'phantom_desktop'?", "premium_3_0", "got 'phantom_desk'"}},
      {"unknown_generator.yaml",
       6,
       "surface.texture.generator",
       {":6:16", "unknown generator", "did you mean 'bricks'?", "vvalley", "got 'brick'"}},
      {"unknown_generator_param.yaml",
       10,
       "surface.texture.params.mortar_width",
       {":10:7", "unknown field 'mortar_width'", "did you mean 'mortar'?", "mortar_depth", "extent"}},
      {"generator_param_out_of_range.yaml",
       8,
       "surface.texture.params.angle_deg",
       {":8:25", "out of range", "[10, 170] deg", "got '5'"}},
      {"texture_size_not_integer.yaml",
       7,
       "surface.texture.size",
       {":7:11", "not an integer", "[2, 16384]", "got '512.5'"}},
      {"texture_file_missing.yaml",
       6,
       "surface.texture.file",
       {":6:11", "file not found", "bad_scenes/no_such_texture.png", "relative paths resolve against",
        "got 'no_such_texture.png'"}},
      {"file_and_generator.yaml", 6, "surface.texture", {":6:5", "both file and generator", "exactly one"}},
      {"relief_zero_max_depth.yaml",
       7,
       "surface.max_depth",
       {":7:14", "relief surface needs a positive max_depth", "(0, 0.1] m", "got '0'"}},
      {"max_depth_fraction_too_deep.yaml",
       7,
       "surface.max_depth_fraction",
       {":7:23", "too deep for a texture", "at most 0.1 m", "up to 0.25 of size[0] = 0.4 m", "'0.5' (0.2 m)"}},
      {"max_depth_and_fraction.yaml",
       7,
       "surface.max_depth_fraction",
       {":7:23", "both max_depth and max_depth_fraction", "a fraction of size[0]"}},
      {"max_depth_fraction_negative.yaml",
       6,
       "surface.max_depth_fraction",
       {":6:23", "out of range", "(0, 1] of size[0]", "got '-0.01'"}},
      {"vrpn_without_address.yaml",
       6,
       "device.address",
       {":6:1", "missing required field for type: vrpn", "Phantom0@localhost:3883"}},
      {"vrpn_malformed_address.yaml",
       8,
       "device.address",
       {":8:12", "malformed VRPN address", "no '@'", "DEVICE@HOST[:PORT]", "got 'localhost:3883'"}},
      {"sim_with_address.yaml", 8, "device.address", {":8:12", "applies only to type: vrpn"}},
      {"damping_above_model.yaml",
       8,
       "device.damping",
       {":8:12", "out of range", "[0, 4] N·s/m", "model touch", "got '6.5'"}},
      {"sim_integration_too_slow.yaml",
       8,
       "device.sim.integration_hz",
       {":8:21", "out of range", "[10000, 1000000] Hz", "got '1000'"}},
      {"script_press_outside_surface.yaml",
       9,
       "device.script[1].press.position",
       {":9:25", "outside the surface", "[-0.1, 0.1] x [-0.05, 0.05] m", "got [0, 0.08]"}},
      {"script_force_above_peak.yaml",
       13,
       "device.script[0].stroke.force",
       {":13:16", "out of range", "(0, 3.3] N", "peak force of phantom_omni", "got '5'"}},
      {"script_two_actions.yaml",
       8,
       "device.script[0]",
       {":8:7", "more than one action", "exactly one of press, stroke, path_file, hold"}},
      {"script_path_file_missing.yaml",
       8,
       "device.script[0].path_file",
       {":8:18", "file not found", "paths/missing_path.csv", "t_s, x_m, y_m, force_n"}},
      {"duplicate_object_names.yaml",
       8,
       "objects[1].name",
       {":8:12", "duplicate object name", "objects[0], line 7", "got 'marble'"}},
      {"box_with_radius.yaml", 9, "objects[0].radius", {":9:13", "does not apply to shape box", "size: [x, y, z]"}},
      {"capsule_missing_length.yaml", 7, "objects[0].length", {":7:5", "missing required field", "radius and length"}},
      {"negative_mass.yaml", 10, "objects[0].mass", {":10:11", "out of range", "(0, 1000] kg", "got '-0.03'"}},
      {"infinite_rate.yaml", 7, "rates.visual_hz", {":7:14", "not a finite number", "[1, 1000] Hz", "got '.inf'"}},
      {"vrpn_with_script.yaml", 9, "device.script", {":9:3", "applies only to type: sim", "with type: vrpn"}},
      {"unknown_top_level_key.yaml",
       6,
       "object",
       {":6:1", "unknown field 'object'", "did you mean 'objects'?", "version, name, description"}},
      {"script_unknown_action.yaml",
       9,
       "device.script[1].pres",
       {":9:7", "unknown field 'pres'", "did you mean 'press'?", "press, stroke, path_file, hold"}},
      {"negative_seed.yaml", 5, "surface.texture.seed", {":5:49", "out of range", "an integer in [0, ", "got '-3'"}},
  };
  return cases;
}

class BadSceneTest : public testing::TestWithParam<BadScene> {};

TEST_P(BadSceneTest, ErrorNamesFileLineFieldValueAndExpectation) {
  const BadScene& c = GetParam();
  const std::string path = kDir + c.file;
  try {
    thx::scene::loadScene(path);
    FAIL() << c.file << " loaded without error";
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.where().file, path);
    EXPECT_EQ(e.where().line, c.line) << message;
    EXPECT_GT(e.where().column, 0) << message;
    EXPECT_EQ(e.field(), c.field) << message;
    EXPECT_NE(message.find(path + ":" + std::to_string(c.line) + ":"), std::string::npos) << message;
    for (const std::string& part : c.contains)
      EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
  }
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadSceneTest, testing::ValuesIn(corpus()), [](const auto& param_info) {
  std::string name = param_info.param.file.substr(0, param_info.param.file.find('.'));
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
});

// A file added to the corpus without a table entry would go untested.
TEST(BadSceneCorpus, EveryFileHasAnEntryAndEveryEntryAFile) {
  std::set<std::string> files, listed;
  for (const auto& entry : std::filesystem::directory_iterator(kDir))
    if (entry.path().extension() == ".yaml") files.insert(entry.path().filename().string());
  for (const BadScene& c : corpus()) listed.insert(c.file);
  EXPECT_EQ(files, listed);
  EXPECT_GE(files.size(), 15u);
}

TEST(BadSceneCorpus, EveryMessageIsDistinct) {
  std::set<std::string> problems;
  for (const BadScene& c : corpus()) {
    try {
      thx::scene::loadScene(kDir + c.file);
    } catch (const SceneError& e) {
      std::string m = e.what();
      problems.insert(m.substr(m.find(c.file) + c.file.size()));  // without the file name
    }
  }
  EXPECT_EQ(problems.size(), corpus().size());
}

TEST(LoadScene, MissingSceneFile) {
  try {
    thx::scene::loadScene(kDir + "does_not_exist.yaml");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("does_not_exist.yaml: scene file not found"), std::string::npos) << e.what();
    EXPECT_EQ(e.where().line, 0);
  }
}

TEST(LoadScene, DirectoryIsNotASceneFile) { EXPECT_THROW(thx::scene::loadScene(kDir), SceneError); }

}  // namespace

}  // namespace test_bad_scenes
