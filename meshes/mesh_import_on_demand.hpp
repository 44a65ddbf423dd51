#pragma once
// importMesh with Assimp opened only on first use: a program that loads scenes (hapticd above
// all) links neither Assimp nor its codecs, whose pages (3.3 MB resident at load, even in a plane
// scene) would miss hapticd's memory goal (docs/benchmarks.md). The first mesh file opens the
// mesh import module (libthx_mesh_import_module.so, built with the project: mesh_import_module.cpp)
// and keeps it open for the life of the process.
//
// Where the module is: $THX_MESH_IMPORT_MODULE when set (a path), else the path it was built at.
// Not for real-time threads: opening the module maps files and runs Assimp's constructors.
#include <string>

#include "meshes/mesh_import.hpp"

namespace thx::mesh {

// The path importMeshOnDemand opens.
std::string meshImportModulePath();

// A mesh import module, opened once (dlopen; never closed: Assimp's static state lives as long
// as the process, and a closed module's leak reports would have no stacks).
class MeshImportModule {
 public:
  // Throws thx::Error(Io) naming the path when it cannot be opened (dlerror's reason) or has no
  // entry point (not a mesh import module).
  explicit MeshImportModule(const std::string& module_path);

  // As importMesh (the same refusals, the same thx::Error kinds and messages); also thx::Error(Io)
  // naming the module when it was built from other headers than this program.
  TexturedMesh import(const std::string& path, const ImportOptions& options = {}) const;

 private:
  std::string module_path_;
  void* entry_ = nullptr;
};

// importMesh through the module at meshImportModulePath(), opened by the first call that needs
// it (thread-safe; a module that failed to open is tried again by the next call).
TexturedMesh importMeshOnDemand(const std::string& path, const ImportOptions& options = {});

}  // namespace thx::mesh
