// importMeshOnDemand and MeshImportModule (meshes/mesh_import_on_demand.hpp): a file read
// through the module is the mesh importMesh reads in this process, a refusal keeps its kind and
// message, and a module that cannot be used is a clear error naming it.
#include <gtest/gtest.h>

#include <string>

#include "base/error.hpp"
#include "meshes/mesh_import.hpp"
#include "meshes/mesh_import_on_demand.hpp"
#include "tests/support/process_environment.hpp"

namespace test_mesh_import_on_demand {

using namespace thx;
using namespace thx::mesh;

namespace {

const std::string kDir = std::string(THX_TEST_DATA_DIR) + "/meshes/";

// "<kind>: <message>" of the refusal, or "accepted".
template <class Import>
std::string verdict(Import import) {
  try {
    import();
    return "accepted";
  } catch (const Error& e) {
    return std::to_string(static_cast<int>(e.kind())) + ": " + e.what();
  }
}

}  // namespace

TEST(MeshImportOnDemand, ReadsTheMeshImportMeshReads) {
  ImportOptions options;
  options.unit_m = 0.01;
  options.projection = UvProjection::Cylindrical;
  const TexturedMesh direct = importMesh(kDir + "cube.obj", options);
  const TexturedMesh loaded = importMeshOnDemand(kDir + "cube.obj", options);
  // Read there, not by this executable's own importMesh.
  EXPECT_TRUE(test::isMapped("libthx_mesh_import_module.so"));
  EXPECT_EQ(loaded.source, direct.source);
  ASSERT_EQ(loaded.positions.size(), direct.positions.size());
  ASSERT_EQ(loaded.triangles.size(), direct.triangles.size());
  ASSERT_TRUE(loaded.hasFrames());
  EXPECT_EQ(loaded.triangles, direct.triangles);
  for (std::size_t v = 0; v < direct.positions.size(); ++v) {
    EXPECT_EQ(loaded.positions[v], direct.positions[v]) << v;
    EXPECT_EQ(loaded.uvs[v], direct.uvs[v]) << v;
    EXPECT_EQ(loaded.normals[v], direct.normals[v]) << v;
    EXPECT_EQ(loaded.tangents[v], direct.tangents[v]) << v;
    EXPECT_EQ(loaded.handedness[v], direct.handedness[v]) << v;
  }
}

TEST(MeshImportOnDemand, RefusalsKeepTheirKindAndMessage) {
  for (const std::string file : {"nan_vertex.obj", "flipped_face.obj", "lines_only.obj", "no_such.obj", "cube.xyz"}) {
    ImportOptions options;
    options.limits.require_closed = true;
    const std::string direct = verdict([&] { return importMesh(kDir + file, options); });
    EXPECT_NE(direct, "accepted") << file;
    EXPECT_EQ(verdict([&] { return importMeshOnDemand(kDir + file, options); }), direct) << file;
  }
}

TEST(MeshImportOnDemand, TheModulesPathComesFromTheEnvironmentWhenSet) {
  const std::string built = [] {
    test::ScopedEnv empty("THX_MESH_IMPORT_MODULE", "");  // empty counts as unset
    return meshImportModulePath();
  }();
  EXPECT_NE(built.find("libthx_mesh_import_module.so"), std::string::npos) << built;
  test::ScopedEnv other("THX_MESH_IMPORT_MODULE", "/elsewhere/module.so");
  EXPECT_EQ(meshImportModulePath(), "/elsewhere/module.so");
}

TEST(MeshImportOnDemand, AModuleThatCannotBeUsedIsAClearError) {
  const std::string missing = kDir + "no_such_module.so";
  const std::string refused = verdict([&] { return MeshImportModule(missing); });
  EXPECT_EQ(refused.rfind(std::to_string(static_cast<int>(Error::Kind::Io)) + ": mesh import module " + missing +
                              ": cannot open: ",
                          0),
            0u)
      << refused;
  // A shared object that is not a module (the C maths library, found by its soname).
  const std::string not_module = verdict([] { return MeshImportModule("libm.so.6"); });
  EXPECT_NE(not_module.find("mesh import module libm.so.6: has no entry point thx_mesh_import_v1"), std::string::npos)
      << not_module;
  // The module built with the project opens and reads.
  const MeshImportModule built(meshImportModulePath());
  EXPECT_EQ(built.import(kDir + "cube.obj").triangles.size(), 12u);
}

}  // namespace test_mesh_import_on_demand
