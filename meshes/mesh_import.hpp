#pragma once
// Mesh files through Assimp (docs/meshes.md, "Mesh files"): OBJ, PLY, glTF 2.0 (.gltf, .glb) and
// STL, picked by the file's extension, flattened into one mesh with its node transforms applied,
// triangulated, scaled to metres, checked (mesh_check.hpp) and given its vertex frames
// (buildVertexFrames). Only the reader of the extension's format is registered with Assimp: a
// file of another format, or one renamed, never reaches the rest of Assimp's parsers. A PLY is
// checked and rewritten first (ply_guard.hpp). Every refusal is a thx::Error naming the file: Io
// for a file that cannot be read or is larger than max_file_bytes, Config for the rest.
#include <cstddef>
#include <string>

#include "meshes/mesh_check.hpp"
#include "meshes/textured_mesh.hpp"

namespace thx::mesh {

// Texture coordinates for a file that has none (ignored when it has them).
enum class UvProjection { None, Planar, Cylindrical, Spherical };

struct ImportOptions {
  double unit_m = 1.0;                           // metres per file unit (0.001 for a file in millimetres)
  UvProjection projection = UvProjection::None;  // for a file without texture coordinates
  double tile_m = 0.05;                          // metres per uv unit for a projection
  MeshLimits limits;
  std::size_t max_file_bytes = std::size_t(256) << 20;
};

// Reads OBJ, PLY, glTF 2.0 (.gltf/.glb) or STL, by the path's extension (any case). Files the
// mesh names beside it (a .gltf's .bin buffers) are read from the path's folder, each within
// max_file_bytes; an OBJ's material library (.mtl) never is (materials are not used). Throws
// thx::Error naming the path: Io for a file that cannot be opened or read or is larger than
// max_file_bytes (refused before reading), Config for an unknown extension, anything Assimp
// refuses (its message quoted), a PLY whose counts its data does not hold, no triangles, no
// texture coordinates without a projection, more than limits.max_triangles (refused before
// copying) and everything checkMesh refuses.
TexturedMesh importMesh(const std::string& path, const ImportOptions& options = {});

// The same from bytes in memory: format_hint is the extension without its dot ("obj", "ply",
// "stl", "gltf", "glb"), `source` names the bytes in messages and in the mesh. Nothing is read
// from the file system: a .gltf must embed its buffers (data: URIs).
TexturedMesh importMeshFromMemory(const void* data, std::size_t size, const std::string& format_hint,
                                  const std::string& source, const ImportOptions& options = {});

// "none", "planar", "cylindrical" or "spherical"; throws thx::Error(Config) naming the value.
UvProjection parseUvProjection(const std::string& text);

}  // namespace thx::mesh
