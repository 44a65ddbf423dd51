// modal-analyze --mesh, run as a separate process (issue 29): the modes of the solid inside a
// built-in shape and inside a mesh file, the cache on the second run, and the errors a user sees
// (exit status, the file and what was expected).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"

namespace thx::audio::test_modal_analyze_mesh_cli {
namespace {

namespace fs = std::filesystem;

class ModalAnalyzeMeshCli : public ::testing::Test {
 protected:
  void SetUp() override {
    tool_ = THX_MODAL_ANALYZE;  // tests/audio/CMakeLists.txt: built before this test
    ASSERT_TRUE(fs::exists(tool_)) << "modal-analyze not built at " << tool_;
  }
  std::string path(const std::string& name) const { return dir_.file(name); }
  int run(std::vector<std::string> args) {
    args.insert(args.begin(), tool_.string());
    thx::test::ToolRun r = thx::test::runTool(args, dir_.path(), 120.0);
    out_ = std::move(r.out);
    err_ = std::move(r.err);
    return r.status;
  }
  fs::path tool_;
  thx::test::TempDir dir_{"thx_modal_analyze_mesh"};
  std::string out_, err_;
};

TEST_F(ModalAnalyzeMeshCli, ABuiltInShapesSolidIsAnalysedAndCached) {
  const std::vector<std::string> args{"--mesh", "box", "--radius", "0.02", "--segments", "16", "--modes", "8",
                                      "--cache-dir", path("cache")};
  ASSERT_EQ(run(args), 0) << err_;
  EXPECT_NE(out_.find("# box: steel, Tet10"), std::string::npos) << out_;
  EXPECT_NE(out_.find("solved in"), std::string::npos) << out_;
  EXPECT_NE(err_.find("surface triangles"), std::string::npos) << err_;  // the tetrahedra's progress line
  const std::string first = out_.substr(out_.find('\n'));
  ASSERT_EQ(run(args), 0) << err_;
  EXPECT_NE(out_.find("read from cache"), std::string::npos) << out_;  // Gmsh fills it the same way again
  EXPECT_EQ(out_.substr(out_.find('\n')), first);
}

TEST_F(ModalAnalyzeMeshCli, AMeshFileInMillimetresIsRead) {
  // A closed tetrahedron-shaped solid, 40 mm edges, wound outwards, with texture coordinates.
  std::ofstream(path("tet.obj")) << "v 0 0 0\nv 40 0 0\nv 0 40 0\nv 0 0 40\nvt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\n"
                                    "f 1/1 3/3 2/2\nf 1/1 2/2 4/4\nf 1/1 4/4 3/3\nf 2/2 3/3 4/4\n";
  ASSERT_EQ(run({"--mesh", path("tet.obj"), "--mesh-unit", "0.001", "--max-edge", "0.01", "--modes", "6", "--no-cache",
                 "--quiet"}),
            0)
      << err_;
  EXPECT_NE(out_.find("tet.obj: steel, Tet10"), std::string::npos) << out_;
}

TEST_F(ModalAnalyzeMeshCli, AnOpenMeshOrAMissingFileIsNamedAndExitsOne) {
  std::ofstream(path("open.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\n"
                                     "f 1/1 3/3 2/2\nf 1/1 2/2 4/4\nf 1/1 4/4 3/3\n";
  EXPECT_EQ(run({"--mesh", path("open.obj"), "--no-cache"}), 1);
  EXPECT_NE(err_.find("open.obj"), std::string::npos) << err_;
  EXPECT_NE(err_.find("closed surface of a solid"), std::string::npos) << err_;
  EXPECT_EQ(run({"--mesh", path("missing.obj"), "--no-cache"}), 1);
  EXPECT_NE(err_.find("missing.obj"), std::string::npos) << err_;
  EXPECT_EQ(run({"--mesh", "box", "--cells", "2"}), 2);  // a usage error
  EXPECT_NE(err_.find("--max-edge"), std::string::npos) << err_;
}

// --scene on a mesh scene: its surface is the solid the scene's mesh encloses (a coarse bowl: the
// cap at 48 segments is test_surface_tetrahedra.cpp's); an open mesh is refused naming the scene
// and what to change.
TEST_F(ModalAnalyzeMeshCli, AMeshScenesSurfaceIsTheSolidItsMeshEncloses) {
  const std::string surface = "surface:\n  size: [0.04, 0.04]\n  texture: {generator: bricks, size: 32}\n  material: ceramic\n";
  std::ofstream(path("bowl.yaml")) << "version: 1\nname: bowl\n" << surface
                                   << "  mesh: {generator: bowl, size: 0.06, segments: 12, closed: true}\n";
  ASSERT_EQ(run({"--scene", path("bowl.yaml"), "--modes", "6", "--no-cache", "--quiet"}), 0) << err_;
  EXPECT_NE(out_.find("surface      ceramic"), std::string::npos) << out_;
  EXPECT_NE(out_.find("pen "), std::string::npos) << out_;
  // An open tube has no inside.
  std::ofstream(path("tube.yaml")) << "version: 1\nname: tube\n" << surface
                                   << "  mesh: {generator: cylinder, size: 0.02, segments: 16}\n";
  EXPECT_EQ(run({"--scene", path("tube.yaml"), "--modes", "6", "--no-cache", "--quiet"}), 1);
  EXPECT_NE(err_.find("tube.yaml"), std::string::npos) << err_;
  EXPECT_NE(err_.find("closed surface of a solid"), std::string::npos) << err_;
}

}  // namespace
}  // namespace thx::audio::test_modal_analyze_mesh_cli
