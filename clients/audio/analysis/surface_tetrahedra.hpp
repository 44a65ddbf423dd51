#pragma once
// The solid inside a closed triangle mesh as tetrahedra, for modal analysis of any shape (issue
// 29): the mesh is checked (meshes/mesh_check.hpp, closed), welded by position (a texture seam's
// split vertices are one point of the solid), and handed to Gmsh's C++ API (Debian's
// libgmsh-dev), whose 3D Delaunay mesher fills it and whose optimiser improves the worst
// tetrahedra. The surface triangles are kept as the solid's boundary (a discrete surface: Gmsh
// does not remesh it), so the solid is exactly the polyhedron the mesh describes. Quadratic
// elements get their edge midpoints here, on the straight edges (no mesher written here: Gmsh
// places every node of the linear mesh).
//
// Not real-time code; not thread-safe (Gmsh is one global model per process: one call at a time).
// Build once per body; the modal cache (modal_cache.hpp) keeps the modes.
#include <string>

#include "clients/audio/analysis/tet_mesh.hpp"
#include "meshes/textured_mesh.hpp"

namespace thx::audio {

struct TetrahedraSettings {
  ElementOrder order = ElementOrder::Quadratic;
  // Longest tetrahedron edge Gmsh aims for inside the solid, metres; 0: sized from the surface
  // triangles alone (Gmsh's sizes interpolated from the boundary's).
  double max_edge_m = 0.0;
  // Refuse a mesh that would make more tetrahedra than this (memory and solve time grow with it).
  std::size_t max_tets = 2'000'000;
};

// Throws ModalError naming `name`, the mesh's source and what to change: a surface that is not
// closed or not consistently wound (the mesh check's message), one Gmsh cannot fill (a
// self-intersecting surface, a part too thin for the mesher: Gmsh's own reason quoted), too many
// tetrahedra, or none at all.
TetMesh tetrahedraOfSurface(const std::string& name, const mesh::TexturedMesh& surface,
                            const TetrahedraSettings& settings = {});

}  // namespace thx::audio
