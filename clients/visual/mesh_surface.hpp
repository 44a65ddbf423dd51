#pragma once
// A textured triangle mesh as the visual client draws it (issue 28): the mesh with its vertex
// tangent frames (meshes/textured_mesh.hpp), how many metres one texture tile spans on it, the
// texture, and where the mesh stands. The GL renderer (mesh_surface_renderer.*) and the CPU
// reference (mesh_reference.*) read the same description, so they draw the same surface.
//
// The texture always wraps: a mesh's uv counts tiles (1 = one tile), and its generators make whole
// tiles meet at their seams. The filter is the scene's.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "meshes/textured_mesh.hpp"
#include "textures/textured_surface.hpp"

namespace thx::visual {

struct MeshSurface {
  const mesh::TexturedMesh* mesh = nullptr;  // with frames (hasFrames()); must outlive the users
  // Metres per uv unit along u and v (GeneratedMesh::tile_used_m): the tile the map's normals
  // were made for. Where the mesh's uv lays the texture at another scale (a sphere towards its
  // poles, a lathe's narrow parts, a file's uneven uv), each face is drawn at its own scale
  // (mesh::metresPerUv: the relief's parallax) with the normals turned to the slopes as laid
  // there (TexturedSurface::setNormalsMadeFor), as the haptic renderer feels it.
  Eigen::Vector2d tile_m{0.05, 0.05};
  const tex::TextureMap* map = nullptr;  // must outlive the users
  tex::Filter filter = tex::Filter::Bilinear;
  bool use_relief = false;  // read the map's depth as relief (needs a relief map)
  Eigen::Isometry3d mesh_to_world = Eigen::Isometry3d::Identity();

  tex::SampleOptions sampling() const { return {filter, tex::Address::Wrap}; }
  bool usesRelief() const { return use_relief && map != nullptr && map->isRelief(); }
  // The texture as a wrapped surface one tile large: the tangent plane at a mesh point, in
  // "tangent metres" (x = u * tile_m.x, y = v * tile_m.y, z along the normal). The CPU reference
  // and the image comparison read the map through it.
  tex::TexturedSurface tangentPlane() const {
    tex::PlaneMapping mapping;
    mapping.size_m = tile_m;
    return tex::TexturedSurface(*map, mapping, sampling(), use_relief);
  }
  // The tangent plane at a face laid at `metres_per_uv` (mesh::metresPerUv), the normals turned
  // from tile_m's slopes to that scale's.
  tex::TexturedSurface chartAt(const Eigen::Vector2d& metres_per_uv) const {
    tex::PlaneMapping mapping;
    mapping.size_m = metres_per_uv;
    tex::TexturedSurface chart(*map, mapping, sampling(), use_relief);
    chart.setNormalsMadeFor(tile_m);
    return chart;
  }
};

// Throws thx::Error (Config) naming what is missing: no mesh, no frames, no map, a tile not > 0.
void checkMeshSurface(const MeshSurface& surface);

}  // namespace thx::visual
