// The mesh import module (libthx_mesh_import_module.so): importMesh behind one C entry point, so
// that a program opens Assimp only when a scene names a mesh file (mesh_import_on_demand.hpp).
// Linked with its own copies of the project code it needs (no symbol but the entry point is
// exported), and with Assimp.
#include <exception>
#include <new>

#include "base/error.hpp"
#include "meshes/mesh_import_call.hpp"

extern "C" __attribute__((visibility("default"))) int thx_mesh_import_v1(thx::mesh::MeshImportCall* call) {
  using thx::mesh::MeshImportCall;
  if (call == nullptr || call->call_bytes != sizeof(MeshImportCall) ||
      call->options_bytes != sizeof(thx::mesh::ImportOptions) || call->mesh_bytes != sizeof(thx::mesh::TexturedMesh)) {
    return 2;
  }
  try {
    *call->mesh = thx::mesh::importMesh(*call->path, *call->options);
    return 0;
  } catch (const thx::Error& e) {
    *call->error = e.what();
    call->error_kind = static_cast<int>(e.kind());
    return 1;
  } catch (const std::exception& e) {  // bad_alloc, or a library's own exception type
    *call->error = *call->path + ": " + e.what();
    call->error_kind = static_cast<int>(thx::Error::Kind::Io);
    return 3;
  }
}
