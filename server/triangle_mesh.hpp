#pragma once
// A triangle mesh in a textured plane's local frame, and the relief displaced as an N x N grid:
// what a mesh renderer (mesh_god_object.hpp) feels instead of the texture. Built once, before the
// servo runs (allocates).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "textures/textured_surface.hpp"

namespace thx::srv {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;                  // plane-local, metres
  std::vector<std::array<std::uint32_t, 3>> triangles;    // counter-clockwise seen from outside (+z)
  // Bytes of the two arrays (the mesh's size in memory, Table 1's "mesh size").
  std::size_t bytes() const {
    return vertices.size() * sizeof(vertices[0]) + triangles.size() * sizeof(triangles[0]);
  }
};

// N x N quads over the map's rectangle, each vertex on the surface the senses share (z = height
// the surface samples there: -depth for a relief), each quad split along the same diagonal as
// the visual client's `mesh:N` (clients/visual/mesh_builders.cpp): (r,c),(r,c+1),(r+1,c+1) and
// (r,c),(r+1,c+1),(r+1,c). Throws thx::Error (Config) for n < 1 or n > 4096.
TriangleMesh reliefGridMesh(const tex::TexturedSurface& surface, int n);

}  // namespace thx::srv
