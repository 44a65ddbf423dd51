// Haptic time per tick on the relief displaced as N x N meshes (god object + BVH) beside the
// texture renderer on the same path: Table 1's haptic column for the meshes (issue 16;
// docs/benchmarks.md part 2c). benchmarks/mesh_haptic_time.hpp has the protocol.
#include <cstdio>
#include <string>
#include <vector>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"
#include "benchmarks/mesh_haptic_time.hpp"
#include "server/scene_device.hpp"

namespace {

using namespace thx;

constexpr const char* kHelp = R"(usage: bench_mesh_haptic [--scene FILE] [--size N] [--meshes N,N,...] [--passes P]
                         [--csv FILE] [--json FILE] [--md FILE]

Haptic time per servo tick on the scene's relief displaced as N x N triangle meshes (the visual
client's mesh:N), rendered by the god object over a BVH (server/mesh_god_object.hpp), beside the
texture renderer (hapticd's configuration for the scene) on the same tip path: 16 strokes in
contact, 0.5 mm under the surface at 50 mm/s (benchmarks/mesh_haptic_time.hpp).

  --scene FILE   a scene with a relief surface (default: scenes/default.yaml, bricks)
  --size N       the texture's texels per side (a generated texture only; default: the scene's)
  --meshes LIST  mesh resolutions (quads per side; default 256,512: Table 1's meshes)
  --passes P     timed passes per renderer, the fastest kept (default 11)
  --csv/--json/--md FILE  results (CSV: one row per mesh)
Prints the CSV to stdout when no file is given.
)";


void write(const std::string& path, const std::string& text) {
  if (path.empty()) return;
  bench::writeTextFile(path, text);
}

int run(int argc, char** argv) {
  std::string scene_path = bench::sourceDir() + "/scenes/default.yaml", csv, json, md;
  int size = 0, passes = 11;
  std::vector<int> meshes{256, 512};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw UsageError(a + " needs a value");
    const std::string val = argv[++i];
    if (a == "--scene") scene_path = val;
    else if (a == "--size") size = int(cli::parseInteger(a, val, 2, 8192));
    else if (a == "--meshes") meshes = cli::parseIntegerList(a, val, 1, 4096);
    else if (a == "--passes") passes = int(cli::parseInteger(a, val, 1, 100));
    else if (a == "--csv") csv = val;
    else if (a == "--json") json = val;
    else if (a == "--md") md = val;
    else throw UsageError("unknown option '" + a + "'");
  }
  const bench::SceneTexture st = bench::loadSceneTexture(scene_path, size);
  const bench::PlacedSurface placed(st.scene, st.map(), true);
  if (!placed.surface.usesRelief()) throw Error(Error::Kind::Config, scene_path + ": the surface's texture has no relief depth");
  const srv::RendererConfig config = srv::servoRigConfigFor(st.scene).renderer;
  const int tex_n = st.map().width();

  std::vector<bench::MeshHapticTime> rows;
  for (int n : meshes) {
    std::fprintf(stderr, "bench_mesh_haptic: %d² mesh of the %d² texture\n", n, tex_n);
    rows.push_back(bench::measureMeshHapticTime(placed.surface, n, config, passes));
  }

  std::string c =
      "scene,texture_size,mesh_n,vertices,triangles,mesh_bytes,bvh_bytes,bvh_depth,build_ms,ticks,contact_share,"
      "mesh_ns_per_tick,mesh_p99_ns,texture_ns_per_tick\n";
  for (const auto& r : rows) {
    c += bench::fmt("%s,%d,%d,%zu,%zu,%zu,%zu,%d,%.1f,%zu,%.3f,%.1f,%.1f,%.1f\n", st.scene.name.c_str(), tex_n, r.mesh_n,
                    r.vertices, r.triangles, r.mesh_bytes, r.bvh_bytes, r.bvh_depth, r.build_ms, r.ticks,
                    r.contact_share, r.ns_per_tick, r.p99_ns, r.texture_ns_per_tick);
  }
  if (csv.empty() && json.empty() && md.empty()) std::fputs(c.c_str(), stdout);
  write(csv, c);

  std::string j = "{\n  \"benchmark\": \"haptic time per tick on N x N meshes (god object + BVH) and the texture\",\n";
  j += "  \"machine\": \"" + bench::machineDescription() + "\",\n  \"date\": \"" + bench::isoTimeNow() + "\",\n";
  j += bench::fmt("  \"scene\": \"%s\",\n  \"texture_size\": %d,\n  \"stiffness_n_per_m\": %g,\n  \"rows\": [\n",
                  st.scene.name.c_str(), tex_n, config.stiffness_n_per_m);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    j += bench::fmt("    {\"mesh_n\": %d, \"vertices\": %zu, \"triangles\": %zu, \"mesh_bytes\": %zu, \"bvh_bytes\": %zu, "
                    "\"bvh_depth\": %d, \"build_ms\": %.1f, \"ticks\": %zu, \"contact_share\": %.3f, "
                    "\"mesh_ns_per_tick\": %.1f, \"mesh_p99_ns\": %.1f, \"texture_ns_per_tick\": %.1f}%s\n",
                    r.mesh_n, r.vertices, r.triangles, r.mesh_bytes, r.bvh_bytes, r.bvh_depth, r.build_ms, r.ticks,
                    r.contact_share, r.ns_per_tick, r.p99_ns, r.texture_ns_per_tick, i + 1 < rows.size() ? "," : "");
  }
  j += "  ]\n}\n";
  write(json, j);

  std::string m = bench::fmt("Scene `%s`, %d² texture, k = %g N/m; machine: %s; measured %s.\n\n", st.scene.name.c_str(),
                             tex_n, config.stiffness_n_per_m, bench::machineDescription().c_str(),
                             bench::isoTimeNow().c_str());
  m += "| mesh | vertices | triangles | mesh + BVH (MB) | build (ms) | god object ns/tick | p99 ns | texture ns/tick | "
       "mesh / texture |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    m += bench::fmt("| %d² | %zu | %zu | %.1f + %.1f | %.0f | %.0f | %.0f | %.0f | %.2f |\n", r.mesh_n, r.vertices,
                    r.triangles, double(r.mesh_bytes) / 1e6, double(r.bvh_bytes) / 1e6, r.build_ms, r.ns_per_tick,
                    r.p99_ns, r.texture_ns_per_tick, r.ns_per_tick / r.texture_ns_per_tick);
  }
  write(md, m);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Scene, texture and file errors arrive as std::exception too: named like thx::Error's.
  try {
    return thx::bench::benchMain(argc, argv, kHelp, "bench_mesh_haptic", run);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_mesh_haptic: %s\n", e.what());
    return 1;
  }
}
