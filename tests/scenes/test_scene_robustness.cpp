// Bad input gets a SceneError and nothing worse (docs/design.md §4 rule 6): every truncation of a
// real scene, and every value in it replaced by something hostile, either loads or throws
// SceneError with a location; never another exception, a crash or a sanitizer report.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "scenes/scene_loader.hpp"

namespace test_scene_robustness {

namespace {

using namespace thx::scene;

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

const std::string kDefault = std::string(THX_SOURCE_DIR) + "/scenes/default.yaml";
const std::string kBaseDir = std::string(THX_SOURCE_DIR) + "/scenes";

// Returns true if it loaded; fails the test on anything but success or a located SceneError.
bool loadsOrFailsCleanly(const std::string& text, const std::string& what) {
  try {
    parseScene(text, "fuzz.yaml", kBaseDir);
    return true;
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("fuzz.yaml", 0), 0u) << what << ": " << e.what();
    return false;
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": escaped as a non-scene error: " << e.what();
    return false;
  }
}

TEST(SceneRobustness, EveryTruncationLoadsOrFailsCleanly) {
  const std::string text = readFile(kDefault);
  ASSERT_FALSE(text.empty());
  int loaded = 0;
  for (std::size_t n = 0; n <= text.size(); n += 5)
    loaded += loadsOrFailsCleanly(text.substr(0, n), "prefix " + std::to_string(n));
  EXPECT_GT(loaded, 0);
  EXPECT_TRUE(loadsOrFailsCleanly(text, "whole file"));
}

TEST(SceneRobustness, HostileValuesAreRejectedWithTheirLine) {
  const std::string text = readFile(kDefault);
  const std::regex number(R"([-+]?[0-9]+(\.[0-9]+)?(e-?[0-9]+)?)");
  const std::vector<std::string> hostile = {
      "abc", ".nan", "-.inf", "1e999", "-1", "0", "[1, 2]", "{a: 1}", "''", "1e308", "99999999999999999999", "~"};
  int checked = 0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), number); it != std::sregex_iterator(); ++it) {
    const std::size_t at = std::size_t(it->position()), len = std::size_t(it->length());
    // Only values: skip digits inside names, comments and the like.
    const std::size_t line_start = text.rfind('\n', at) + 1;
    const std::string line = text.substr(line_start, text.find('\n', at) - line_start);
    if (line.find('#') != std::string::npos && line.find('#') < at - line_start) continue;
    if (line.find(':') == std::string::npos && line.find('-') == std::string::npos) continue;
    for (const std::string& value : hostile) {
      const std::string mutated = text.substr(0, at) + value + text.substr(at + len);
      loadsOrFailsCleanly(mutated, "'" + value + "' at offset " + std::to_string(at));
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
}

TEST(SceneRobustness, DeepNestingIsASyntaxErrorNotAStackOverflow) {
  const std::string deep = "version: 1\nname: " + std::string(100000, '[') + "\n";
  EXPECT_THROW(parseScene(deep, "deep.yaml", ""), SceneError);
}

TEST(SceneRobustness, AnchorsAndAliasesWork) {
  const Scene s = parseScene(R"(version: 1
name: aliases
surface:
  size: &side [0.2, 0.2]
  texture: {generator: bricks, size: 16}
objects:
  - {name: a, shape: sphere, radius: 0.01, mass: 0.03, position: &p [0, 0, 0.05]}
  - {name: b, shape: sphere, radius: 0.01, mass: 0.03, position: *p}
)",
                             "a.yaml", "");
  EXPECT_EQ(s.objects[1].pose.position_m, s.objects[0].pose.position_m);
}

}  // namespace

}  // namespace test_scene_robustness
