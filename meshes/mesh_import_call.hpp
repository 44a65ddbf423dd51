#pragma once
// The call between importMeshOnDemand (mesh_import_on_demand.hpp) and the mesh import module
// (mesh_import_module.cpp): one C entry point taking this struct, so that opening the module needs
// one dlsym. Both sides are built together from these headers; the byte counts let the module
// refuse a caller built from other ones (a stale module found through THX_MESH_IMPORT_MODULE).
#include <cstddef>
#include <string>

#include "meshes/mesh_import.hpp"

namespace thx::mesh {

struct MeshImportCall {
  std::size_t call_bytes = sizeof(MeshImportCall);
  std::size_t options_bytes = sizeof(ImportOptions);
  std::size_t mesh_bytes = sizeof(TexturedMesh);
  const std::string* path = nullptr;
  const ImportOptions* options = nullptr;
  TexturedMesh* mesh = nullptr;  // filled on success
  std::string* error = nullptr;  // what() of the refusal otherwise
  int error_kind = 0;            // its thx::Error::Kind
};

// The module's entry point: 0 when *mesh was filled, 1 when importMesh refused the file (a
// thx::Error: error and error_kind set), 2 when the call's byte counts are not the module's, 3 on
// any other exception (error set; error_kind Io).
inline constexpr const char* kMeshImportEntry = "thx_mesh_import_v1";
using MeshImportEntry = int (*)(MeshImportCall*);

}  // namespace thx::mesh
