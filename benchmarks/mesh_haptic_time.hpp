#pragma once
// Haptic time per tick on a triangle mesh (Table 1's haptic column for the meshes, issue 16): the
// relief of a surface displaced as an N x N grid (srv::reliefGridMesh, the visual client's
// mesh:N), rendered by the god object over its BVH (server/mesh_god_object.hpp), beside the
// texture renderer (srv::ProxyRenderer) on the very same tip path, so the two times are
// comparable on one machine. bench_mesh_haptic is the command-line front.
//
// The path (meshStrokePath): 16 strokes in contact, each a press from 0.5 mm above the base plane
// down to 0.5 mm under the surface at 20 um per tick, then 400 ticks (20 mm at 50 mm/s) at that
// depth under the surface in a random direction, then a lift; start points and directions from a
// fixed seed, inside the middle half of the map. One tick = one render() call.
// Timing: the path is run `passes` times per renderer, interleaved, each from a reset; every
// chunk of 128 consecutive ticks keeps its fastest pass (a shared machine preempts in bursts), and
// the per-tick time is the sum of the chunks over the ticks.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "server/proxy_renderer.hpp"
#include "textures/textured_surface.hpp"

namespace thx::bench {

struct MeshHapticTime {
  int mesh_n = 0;
  std::size_t vertices = 0, triangles = 0;
  std::size_t mesh_bytes = 0;  // vertices + triangles (TriangleMesh::bytes)
  std::size_t bvh_bytes = 0;   // the hierarchy's nodes, leaf order and planes
  int bvh_depth = 0;
  double build_ms = 0;         // mesh + BVH construction, once
  std::size_t ticks = 0;       // on the path
  double contact_share = 0;    // ticks with a force, god object
  double ns_per_tick = 0;      // god object: per tick over the path, each 128-tick chunk at its fastest pass
  double p99_ns = 0;           // god object: per-tick 99th percentile (one timed pass, timer cost included)
  double texture_ns_per_tick = 0;  // ProxyRenderer (`config`) on the same path, the same way
};

// The tip path described above, plane-local (world = local for an identity placement).
std::vector<Eigen::Vector3d> meshStrokePath(const tex::TexturedSurface& surface, int strokes = 16,
                                            std::uint64_t seed = 16);

// Builds the N x N mesh from `surface` (a relief; throws thx::Error otherwise) and times both
// renderers over meshStrokePath, `passes` passes each, interleaved. `config`'s stiffness and
// damping drive both; its crease settings only the texture renderer.
MeshHapticTime measureMeshHapticTime(const tex::TexturedSurface& surface, int mesh_n, const srv::RendererConfig& config,
                                     int passes = 11);

}  // namespace thx::bench
