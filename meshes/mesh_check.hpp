#pragma once
// The checks every mesh passes before anything uses it (a file's, a generator's): each refusal is a
// thx::Error (Kind::Config) naming mesh.source, the triangle, edge or vertex and what was
// expected (docs/meshes.md, "Checks"). Nothing else escapes for any mesh, however broken.
//
// Edges are matched by the exact position of their ends, not by vertex index: a mesh splits a
// vertex where its texture coordinates jump (a UV sphere's seam, a box's faces), and the two
// copies keep the very same coordinates, so the surface stays closed across the seam.
#include <cstddef>

#include "meshes/textured_mesh.hpp"

namespace thx::mesh {

struct MeshLimits {
  std::size_t max_triangles = 2'000'000;  // stated bound; a file with more is refused
  bool require_closed = false;            // every edge shared by exactly two triangles
};

// Throws thx::Error(Kind::Config) whose message names mesh.source, the element and what was
// expected. In this order: triangles present and within max_triangles; one texture coordinate per
// position; finite positions and texture coordinates; each triangle's vertex indices in range and
// distinct; each triangle's area above 1e-12 x (bounding-box diagonal)^2; neighbouring triangles
// running their shared edge in opposite directions (on every edge of two triangles); and with
// require_closed, no edge of one triangle (a hole) or of more than two (non-manifold). Without
// require_closed, an edge of three or more triangles is allowed and its winding not compared.
void checkMesh(const TexturedMesh& mesh, const MeshLimits& limits = {});

}  // namespace thx::mesh
