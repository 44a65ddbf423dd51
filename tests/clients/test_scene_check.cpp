// thx_client/scene_check: a client compares the server's scene (hello_t) with its own, and finds
// a scene file by name in its scenes folder.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include <vector>

#include "thx_client/scene_check.hpp"

namespace test_scene_check {

namespace {

using namespace thx::client;
namespace fs = std::filesystem;

const SceneIdentity kBricks{"marble_bricks", 0x1234abcd5678ef01ULL};
const SceneIdentity kDefault{"default", 0xfedcba9876543210ULL};

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The check's verdict and every part its message must hold.
void expectCheck(const SceneCheck& c, SceneVerdict verdict, const std::vector<std::string>& parts) {
  SCOPED_TRACE(c.message);
  EXPECT_EQ(c.verdict, verdict);
  EXPECT_EQ(c.ok(), verdict != SceneVerdict::Differs);
  for (const std::string& part : parts) EXPECT_TRUE(has(c.message, part)) << "missing: " << part;
}

thx_msgs::hello_t helloFor(const SceneIdentity& s) {
  thx_msgs::hello_t h{};
  h.server_name = "hapticd@lab1";
  h.scene_name = s.name;
  h.texture_fingerprint = static_cast<std::int64_t>(s.texture_fingerprint);
  return h;
}

TEST(SceneCheck, SameSceneIsOkAndSilent) {
  const SceneCheck c = checkScene(helloFor(kBricks), kBricks, false);
  EXPECT_EQ(c.verdict, SceneVerdict::Same);
  EXPECT_TRUE(c.ok());
  EXPECT_EQ(c.message, "");
}

TEST(SceneCheck, FingerprintSurvivesTheSignedWireField) {
  const thx_msgs::hello_t h = helloFor(kDefault);  // above INT64_MAX: negative on the wire
  EXPECT_LT(h.texture_fingerprint, 0);
  EXPECT_EQ(sceneOf(h).texture_fingerprint, kDefault.texture_fingerprint);
  EXPECT_EQ(sceneOf(h).name, "default");
}

TEST(SceneCheck, AnotherSceneIsAnErrorNamingBoth) {
  expectCheck(checkScene(helloFor(kDefault), kBricks, false), SceneVerdict::Differs,
              {"scene mismatch", "hapticd@lab1 runs scene 'default' (texture fingerprint 0xfedcba9876543210)",
               "this client scene 'marble_bricks' (texture fingerprint 0x1234abcd5678ef01)", "--scene default",
               "--allow-different-scene"});
}

TEST(SceneCheck, SameNameAnotherTextureIsAnError) {
  const SceneIdentity edited{"marble_bricks", kBricks.texture_fingerprint ^ 1};
  expectCheck(checkScene(helloFor(edited), kBricks, false), SceneVerdict::Differs,
              {"texture mismatch", "0x1234abcd5678ef00", "0x1234abcd5678ef01", "differ"});
  // The same texture under another name is another scene (objects, materials, script may differ).
  EXPECT_EQ(checkScene(SceneIdentity{"copy", kBricks.texture_fingerprint}, kBricks, false).verdict,
            SceneVerdict::Differs);
}

TEST(SceneCheck, AllowedDifferenceIsAWarning) {
  expectCheck(checkScene(helloFor(kDefault), kBricks, true), SceneVerdict::DiffersAllowed,
              {"'default'", "'marble_bricks'", "0xfedcba9876543210", "0x1234abcd5678ef01", "allowed"});
  EXPECT_EQ(checkScene(helloFor(kBricks), kBricks, true).verdict, SceneVerdict::Same);
}

TEST(SceneCheck, ServerWithoutAName) {
  thx_msgs::hello_t h = helloFor(kDefault);
  h.server_name.clear();
  EXPECT_TRUE(has(checkScene(h, kBricks, false).message, "hapticd runs scene 'default'"));
}

// A scenes folder of our own, as on another host.
class SceneLookup : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("thx_scene_lookup_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    for (const char* name : {"wood_study", "default", "bricks.v2"}) std::ofstream(dir_ / (std::string(name) + ".yaml")) << "version: 1\n";
    std::ofstream(dir_ / "notes.txt") << "not a scene\n";
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string dir() const { return dir_.string(); }
  fs::path dir_;
};

TEST_F(SceneLookup, NameResolvesToTheFileInTheFolder) {
  EXPECT_EQ(resolveSceneName("wood_study", dir()), (dir_ / "wood_study.yaml").string());
  EXPECT_EQ(resolveSceneName("bricks.v2", dir()), (dir_ / "bricks.v2.yaml").string());
  // The shipped scenes resolve in the shipped folder.
  EXPECT_EQ(resolveSceneName("marble_bricks", std::string(THX_SOURCE_DIR) + "/scenes"),
            std::string(THX_SOURCE_DIR) + "/scenes/marble_bricks.yaml");
}

TEST_F(SceneLookup, UnknownNameListsTheScenesThere) {
  try {
    resolveSceneName("marble_bricks", dir());
    FAIL() << "no error";
  } catch (const SceneLookupError& e) {
    const std::string m = e.what();
    SCOPED_TRACE(m);
    EXPECT_TRUE(has(m, "scene 'marble_bricks' not found"));
    EXPECT_TRUE(has(m, (dir_ / "marble_bricks.yaml").string()));
    EXPECT_TRUE(has(m, "--scenes-dir"));
    EXPECT_TRUE(has(m, "bricks.v2, default, wood_study"));
    EXPECT_FALSE(has(m, "notes"));
  }
}

TEST_F(SceneLookup, MissingFolderIsNamed) {
  try {
    resolveSceneName("default", dir() + "/nowhere");
    FAIL() << "no error";
  } catch (const SceneLookupError& e) {
    EXPECT_TRUE(has(e.what(), "nowhere' does not exist")) << e.what();
  }
}

TEST_F(SceneLookup, NamesFromTheNetworkCannotLeaveTheFolder) {
  for (const std::string& bad : std::vector<std::string>{"", "../default", "/etc/passwd", ".hidden", "a/b", "sp ace",
                                                       "semi;colon", std::string(101, 'a')}) {
    EXPECT_FALSE(isValidSceneName(bad)) << bad;
    try {
      resolveSceneName(bad, dir());
      ADD_FAILURE() << "no error for '" << bad << "'";
    } catch (const SceneLookupError& e) {
      EXPECT_TRUE(has(e.what(), "invalid scene name")) << e.what();
    }
  }
  EXPECT_TRUE(isValidSceneName("marble_bricks"));
  EXPECT_TRUE(isValidSceneName("Study-3.wood"));
}

TEST_F(SceneLookup, ArgumentIsAPathOrAName) {
  const std::string path = (dir_ / "default.yaml").string();
  EXPECT_EQ(resolveSceneArgument(path, "/nonexistent"), path);   // a path: the folder is not used
  EXPECT_EQ(resolveSceneArgument("default", dir()), path);       // a name: looked up in the folder
  EXPECT_THROW(resolveSceneArgument(dir() + "/absent.yaml", dir()), SceneLookupError);
  EXPECT_THROW(resolveSceneArgument("absent.yaml", dir()), SceneLookupError);  // ends in .yaml: a path
  try {
    resolveSceneArgument("absent", dir());
  } catch (const SceneLookupError& e) {
    EXPECT_TRUE(has(e.what(), "scene 'absent' not found")) << e.what();
  }
}

}  // namespace

}  // namespace test_scene_check
