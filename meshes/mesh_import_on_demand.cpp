#include "meshes/mesh_import_on_demand.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <memory>
#include <mutex>

#include "base/error.hpp"
#include "meshes/mesh_import_call.hpp"

#ifndef THX_MESH_IMPORT_MODULE_PATH
#error "THX_MESH_IMPORT_MODULE_PATH: the built module's path (meshes/CMakeLists.txt)"
#endif

namespace thx::mesh {

namespace {

[[noreturn]] void refuseModule(const std::string& module_path, const std::string& why) {
  throw Error(Error::Kind::Io, "mesh import module " + module_path + ": " + why +
                                   " (mesh files are read through it; THX_MESH_IMPORT_MODULE names another)");
}

}  // namespace

std::string meshImportModulePath() {
  const char* env = std::getenv("THX_MESH_IMPORT_MODULE");
  return env != nullptr && *env != '\0' ? std::string(env) : std::string(THX_MESH_IMPORT_MODULE_PATH);
}

MeshImportModule::MeshImportModule(const std::string& module_path) : module_path_(module_path) {
  // RTLD_LOCAL: the module's copies of the project's code and Assimp's symbols stay its own.
  void* handle = dlopen(module_path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* why = dlerror();
    refuseModule(module_path, std::string("cannot open: ") + (why != nullptr ? why : "unknown reason"));
  }
  entry_ = dlsym(handle, kMeshImportEntry);
  if (entry_ == nullptr) refuseModule(module_path, std::string("has no entry point ") + kMeshImportEntry);
}

TexturedMesh MeshImportModule::import(const std::string& path, const ImportOptions& options) const {
  TexturedMesh mesh;
  std::string error;
  MeshImportCall call;
  call.path = &path;
  call.options = &options;
  call.mesh = &mesh;
  call.error = &error;
  const int status = reinterpret_cast<MeshImportEntry>(entry_)(&call);
  switch (status) {
    case 0: return mesh;
    case 1: throw Error(static_cast<Error::Kind>(call.error_kind), error);
    case 2: refuseModule(module_path_, "built from other headers than this program (rebuild the project)");
    default: throw Error(Error::Kind::Io, error);
  }
}

TexturedMesh importMeshOnDemand(const std::string& path, const ImportOptions& options) {
  static std::mutex mutex;
  static std::unique_ptr<MeshImportModule> module;  // null until one opened
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (!module) module = std::make_unique<MeshImportModule>(meshImportModulePath());
  }
  return module->import(path, options);
}

}  // namespace thx::mesh
