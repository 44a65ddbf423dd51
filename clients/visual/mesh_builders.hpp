#pragma once
// Triangle meshes on the CPU: the plane's quad, the displaced N x N grid (mesh mode), and unit
// shapes for objects and the pen (scaled by their model matrix).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "textures/textured_surface.hpp"

namespace thx::visual {

struct MeshData {
  std::vector<Eigen::Vector3f> positions;
  std::vector<Eigen::Vector3f> normals;
  std::vector<std::uint32_t> indices;  // triangles, counter-clockwise seen from outside
};

// The map's rectangle at z = 0 in the plane frame.
MeshData planeQuad(const Eigen::Vector2d& size_m);
// N x N quads over the map's rectangle; each vertex on the surface the senses share (z = -depth
// sampled as the scene samples it) with the sampled normal.
MeshData displacedGrid(const tex::TexturedSurface& surface, int n);
MeshData unitSphere(int slices, int stacks);       // radius 1
MeshData unitBox();                                // edges 1, centred
MeshData unitCylinder(int slices);                 // radius 1, z in [-0.5, 0.5], capped

}  // namespace thx::visual
