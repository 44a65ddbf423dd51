// modal-analyze: one object's audible modes, offline (see kModalHelp in modal_options.cpp).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "base/error.hpp"
#include "clients/audio/analysis/audible_modes.hpp"
#include "clients/audio/analysis/scene_bodies.hpp"
#include "clients/audio/analysis/scene_mesh_body.hpp"
#include "clients/audio/tools/modal_options.hpp"
#include "base/program_main.hpp"
#include "scenes/scene_loader.hpp"

namespace {

using namespace thx::audio;

double t60(double decay_per_s) { return decay_per_s > 0 ? std::log(1000.0) / decay_per_s : INFINITY; }

void writeCsv(const std::string& path, const AudibleModes& modes) {
  std::ofstream out(path);
  if (!out) throw thx::Error(thx::Error::Kind::Io, path + ": cannot be written");
  out << "mode,frequency_hz,decay_per_s,damping_ratio,t60_s,members\n";
  char line[256];
  for (std::size_t k = 0; k < modes.size(); ++k) {
    std::snprintf(line, sizeof line, "%zu,%.6f,%.6g,%.6g,%.6g,%d\n", k, modes.frequency_hz[k], modes.decay_per_s[k],
                  modes.damping_ratio[k], t60(modes.decay_per_s[k]), modes.members[k]);
    out << line;
  }
  if (!out) throw thx::Error(thx::Error::Kind::Io, path + ": write failed");
}

int run(const ModalOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!o.quiet && o.shape == ShapeKind::Mesh)
    std::fprintf(stderr, "modal-analyze: %s: filling the surface with tetrahedra (Gmsh)\n", o.mesh.c_str());
  std::size_t triangles = 0;
  const TetMesh mesh = buildMesh(o, &triangles);
  if (!o.quiet && o.shape == ShapeKind::Mesh)
    std::fprintf(stderr, "modal-analyze: %s: %zu surface triangles, %zu tetrahedra, %zu nodes in %.2f s\n", o.mesh.c_str(),
                 triangles, mesh.tets.size(), mesh.nodes.size(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  AnalysisOptions ao;
  ao.cache_dir = o.cache_dir;
  if (!o.quiet) ao.progress = [](const std::string& line) { std::fprintf(stderr, "modal-analyze: %s\n", line.c_str()); };
  const ModalSolution s = analyse(mesh, o.material, o.settings, ao);
  const AudibleModes modes = audibleModes(s, o.material, o.audible);
  std::printf("# %s: %s, %s, %zu elements, %d DOFs (%d free), %d rigid modes dropped, %ld elastic modes "
              "computed, %zu audible (%d out of band, %d overdamped, %d merged away, %d truncated); %s %.3f s\n",
              mesh.name.c_str(), o.material.name.c_str(), mesh.order == ElementOrder::Linear ? "Tet4" : "Tet10",
              mesh.tets.size(), s.mesh_dofs, s.free_dofs, s.rigid_modes, long(s.omega_rad_per_s.size()), modes.size(),
              modes.dropped_out_of_band, modes.dropped_overdamped, modes.merged_away, modes.truncated,
              s.from_cache ? "read from cache in" : "solved in", s.total_s);
  std::printf("%5s %14s %12s %12s %10s %7s\n", "mode", "frequency_hz", "decay_per_s", "damping", "t60_s", "members");
  for (std::size_t k = 0; k < modes.size(); ++k)
    std::printf("%5zu %14.3f %12.4g %12.4g %10.4g %7d\n", k, modes.frequency_hz[k], modes.decay_per_s[k],
                modes.damping_ratio[k], t60(modes.decay_per_s[k]), modes.members[k]);
  if (!o.csv.empty()) writeCsv(o.csv, modes);
  return 0;
}

// One line per body of the scene: what it is, how many modes it has in the band, the lowest ones.
int runScene(const ModalOptions& o) {
  const thx::scene::Scene scene = thx::scene::loadScene(o.scene);
  SceneMeshOptions mo;
  mo.slab_thickness_m = o.slab_thickness;
  if (o.clamp_edges) mo.clamp_slab = true;
  mo.slab_cells = o.slab_cells;
  mo.slab_layers = o.slab_layers;
  AnalysisOptions ao;
  ao.cache_dir = o.cache_dir;
  if (!o.quiet) ao.progress = [](const std::string& line) { std::fprintf(stderr, "modal-analyze: %s\n", line.c_str()); };
  double total_s = 0;
  std::printf("# %s: %s\n", o.scene.c_str(), scene.name.c_str());
  std::printf("%-12s %-10s %7s %7s %9s %8s  %s\n", "body", "material", "DOFs", "audible", "time_s", "source",
              "lowest audible frequencies (Hz)");
  std::vector<SceneBody> bodies = sceneBodies(scene, mo);
  // A mesh scene's surface is the solid its mesh encloses (Gmsh), not the slab.
  if (scene.surface.mesh) bodies.front() = meshSurfaceBody(scene, mo.order).body;
  for (const SceneBody& b : bodies) {
    const ModalSolution s = analyse(b.mesh, b.material, o.settings, ao);
    const AudibleModes modes = audibleModes(s, b.material, o.audible);
    total_s += s.total_s;
    std::string lowest;
    for (std::size_t k = 0; k < std::min<std::size_t>(modes.size(), 6); ++k) {
      char f[32];
      std::snprintf(f, sizeof f, "%s%.1f", k ? ", " : "", modes.frequency_hz[k]);
      lowest += f;
    }
    if (modes.size() == 0)
      lowest = "none (lowest elastic mode " + std::to_string(long(std::lround(s.frequencyHz(0)))) + " Hz)";
    std::printf("%-12s %-10s %7d %7zu %9.3f %8s  %s%s%s\n", b.mesh.name.c_str(), b.material.name.c_str(), s.mesh_dofs,
                modes.size(), s.total_s, s.from_cache ? "cache" : "solved", lowest.c_str(), b.note.empty() ? "" : "; ",
                b.note.c_str());
  }
  std::printf("# total %.3f s\n", total_s);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return thx::runProgram("modal-analyze", kModalHelp, argc, argv, [](const std::vector<std::string>& args) {
    const ModalOptions o = parseModalOptions(args);
    return o.scene.empty() ? run(o) : runScene(o);
  });
}
