#pragma once
// One fuzzing step for mesh files: importMeshFromMemory (meshes/mesh_import.hpp) of the bytes as
// OBJ, PLY, STL or glTF 2.0, so Assimp's reader for that format (the only one the import
// registers), for PLY first our rewrite (meshes/ply_guard.hpp), then the flattening, the mesh
// check, a projection and the vertex frames. Shared by the libFuzzer target and the short run in
// test_fuzz_mesh_import.cpp.
//
// Input: byte 0 picks the mode (bits 0 and 3: the format, 0 OBJ, 1 PLY, 8 STL, 9 glTF; bit 1: a
// planar projection for a file without texture coordinates; bit 2: require a closed surface),
// the rest is the file (a glTF with its buffers embedded as data: URIs: nothing is read beside it). At most
// kFuzzMaxTriangles triangles are accepted (MeshLimits::max_triangles, checked before the
// triangles are copied): a few bytes of OBJ make a triangle, and more of them reach no other code.
// Properties:
//  1. a refused file raises thx::Error of kind Config whose message names the source (Io, the
//     other kind the import raises, is for files above max_file_bytes, which no input reaches);
//  2. an accepted mesh is what the import promises: 1 to kFuzzMaxTriangles triangles, one
//     texture coordinate and one frame per vertex, finite positions and texture coordinates,
//     unit normals, unit tangents orthogonal to them, handedness +-1, and it passes checkMesh
//     again under the same limits (splitting vertices for their frames keeps it valid).
#include <cmath>
#include <cstdint>
#include <span>
#include <string>

#include "base/error.hpp"
#include "meshes/mesh_check.hpp"
#include "meshes/mesh_import.hpp"
#include "tests/fuzz/failure.hpp"

namespace thx::fuzz {

inline constexpr std::size_t kFuzzMaxTriangles = 4096;

// The format hint a mode byte picks (bits 0 and 3).
inline std::string meshFuzzFormat(std::uint8_t mode) {
  static const char* const kFormats[4] = {"obj", "ply", "stl", "gltf"};
  return kFormats[(mode & 1) | ((mode & 8) >> 2)];
}

namespace mesh_detail {

inline Failure checkImported(const mesh::TexturedMesh& m, const mesh::MeshLimits& limits) {
  if (m.triangles.empty() || m.triangles.size() > kFuzzMaxTriangles) return std::string("accepted a triangle count out of bounds");
  if (!m.hasFrames() || m.uvs.size() != m.positions.size() || m.tangents.size() != m.positions.size() ||
      m.handedness.size() != m.positions.size())
    return std::string("accepted mesh without one texture coordinate and frame per vertex");
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const std::string at = " at vertex " + std::to_string(v);
    if (!m.positions[v].allFinite() || !m.uvs[v].allFinite()) return "non-finite position or uv" + at;
    const Eigen::Vector3d &n = m.normals[v], &t = m.tangents[v];
    if (!(std::fabs(n.norm() - 1.0) < 1e-9) || !(std::fabs(t.norm() - 1.0) < 1e-9)) return "not a unit normal or tangent" + at;
    if (!(std::fabs(n.dot(t)) < 1e-9)) return "tangent not orthogonal to the normal" + at;
    if (m.handedness[v] != 1.0f && m.handedness[v] != -1.0f) return "handedness not +-1" + at;
  }
  try {
    mesh::checkMesh(m, limits);
  } catch (const Error& e) {
    return std::string("the accepted mesh fails its check after the frames were built: ") + e.what();
  }
  return std::nullopt;
}

}  // namespace mesh_detail

inline Failure fuzzMeshImportOnce(std::span<const std::uint8_t> data) {
  if (data.empty()) return std::nullopt;
  const std::uint8_t mode = data[0];
  const std::string format = meshFuzzFormat(mode);
  const std::string source = "fuzz." + format;
  mesh::ImportOptions options;
  options.limits.max_triangles = kFuzzMaxTriangles;
  options.limits.require_closed = (mode & 4) != 0;
  if (mode & 2) {
    options.projection = mesh::UvProjection::Planar;
    options.tile_m = 0.01;
  }
  mesh::TexturedMesh m;
  try {
    m = mesh::importMeshFromMemory(data.data() + 1, data.size() - 1, format, source, options);
  } catch (const Error& e) {
    if (e.kind() != Error::Kind::Config) return std::string("refusal of a kind other than Config: ") + e.what();
    return mustName(e.what(), source, "mesh refusal");
  }
  return mesh_detail::checkImported(m, options.limits);
}

}  // namespace thx::fuzz
