#pragma once
// bench_table1's per-sense costs, all on one surface (a scene's texture): the representations'
// sizes, the physics step, the visual frame and the haptic tick. docs/table1.md defines each.
#include <string>
#include <vector>

#include "benchmarks/bench_rig.hpp"
#include "tools/report/table1_table.hpp"

namespace thx::bench::table1 {

// Sizes. Normal / relief: the map saved as an 8-bit PNG (RGB / RGBA, docs/textures.md) into
// `workdir`, and the map in memory (tex::TextureMap::bytes). Meshes: the visual client's displaced
// grid (clients/visual/mesh_builders.hpp): vertices, and positions + normals + indices in bytes.
struct Sizes {
  std::array<double, kColumns> file_bytes{}, memory_bytes{}, vertices{};
};
Sizes measureSizes(const SceneTexture& st, const std::string& workdir);

struct Timing {
  double median_s = 0;     // median over repetitions of each repetition's median per step / frame / tick
  double cpu_s = 0;        // CPU time per step / frame (this process, every thread)
  double p99_s = 0;        // haptic only: the 99th percentile tick
  std::string note;
};

// Physics: PhysicsWorld::step(1 ms) with a 6 mm glass-like ball rolling at 5 cm/s across the
// bricks on the surface as a normal map, relief map (both at the texture's resolution) and Bullet
// BVH triangle meshes of 256² and 512² quads (bench_physics_grounds.hpp), heights sampled from
// the scene's texture. `steps` timed steps per repetition after 100 untimed ones.
std::array<Timing, kColumns> timePhysics(const SceneTexture& st, int steps, int reps);

// Visual: FrameRenderer::render (it ends with glFinish) at width x height along bench_visual's
// camera path: normal mapping, relief (the client's default steps), mesh:256, mesh:512.
std::array<Timing, kColumns> timeVisual(const SceneTexture& st, int width, int height, int frames);

// Haptic: ProxyRenderer::render alone per servo tick on the contact window of the tip path the
// simulated device took in lock-step (the scene's script), normal and relief, `passes` passes.
// Also returns that relief path (for the mesh renderer's hook).
std::array<Timing, 2> timeHaptics(const SceneTexture& st, int passes, std::vector<dev::DeviceState>& relief_path);

// Haptic time on a mesh: the relief displaced as an N x N grid (srv::reliefGridMesh: the same
// vertices and diagonals as the visual client's mesh:N) rendered by the god object over its BVH
// (server/mesh_god_object.hpp) with hapticd's stiffness and damping for the scene, on `path` (the
// tip path the relief renderer was timed on), timed per tick as timeHaptics times the textures.
Timing timeMeshHaptics(const SceneTexture& st, int mesh_n, const std::vector<dev::DeviceState>& path, int passes);

}  // namespace thx::bench::table1
