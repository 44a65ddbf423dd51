#pragma once
// A scene's surface as it sounds: its texture (smoothed as hapticd smooths it), the surface slab's
// mesh and its audible modes (modal analysis of the scene's surface material, cached as
// modal-analyze caches). Shared by the offline render and the live client.
#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <string>

#include "clients/audio/analysis/audible_modes.hpp"
#include "clients/audio/analysis/modal_analysis.hpp"
#include "clients/audio/analysis/scene_bodies.hpp"
#include "clients/audio/analysis/scene_mesh_body.hpp"
#include "clients/audio/analysis/tet_mesh.hpp"
#include "clients/audio/synthesis/fractal_roughness.hpp"
#include "scenes/scene.hpp"
#include "scenes/scene_surface.hpp"
#include "textures/texture_map.hpp"

namespace thx::audio {

struct SlabSettings {
  std::optional<double> thickness_m;  // unset: the scene's surface.thickness
  int cells = kSlabCells;   // Tet10 cells per side, in the plane
  int layers = kSlabLayers; // Tet10 cells through the thickness
  std::optional<bool> clamp_edges;    // unset: the scene's surface.held
  int modes = 40;          // elastic modes computed
  double sample_rate_hz = 44100.0;
  std::optional<std::string> cache_dir;  // unset: the default cache folder
  bool no_cache = false;
  bool quiet = false;      // no progress lines on stderr
};

struct SurfaceSound {
  scene::Scene scene;
  scene::SceneSurface surface;  // the texture, its scene name and fingerprint (as hapticd's hello names them: a mesh scene's hashes its mesh too)
  TetMesh slab;                 // a mesh scene's: the solid its mesh encloses (scene_mesh_body.hpp)
  AudibleModes modes;
  // A mesh scene (surface.mesh): `slab` is in the mesh's frame, placed in the world by this (the
  // pen's scrape strikes its surface nodes: synthesis/scrape_sites.hpp).
  std::optional<Eigen::Isometry3d> mesh_to_world;
  const tex::TextureMap& map() const { return *surface.map; }
};

// How a mesh scene's surface body is made (meshSurfaceBody, scene_mesh_body.hpp: Gmsh, library
// thx_audio_tetra). Handed in by the programs that sound meshes, so that this library, the live
// client and their tests do not link Gmsh.
using MeshBodyBuilder = std::function<MeshSurfaceBody(const scene::Scene&)>;

// Throws thx::Error naming the scene file or the cause. `check_surface` (if given) sees the
// texture as soon as it is built, before the slab's modal analysis: it may throw to refuse it.
// A mesh scene's surface is the body `mesh_body` makes of it (the solid its closed mesh encloses);
// without one, a mesh scene is refused by name (scene::requirePlaneSurface).
SurfaceSound buildSurfaceSound(const std::string& scene_file, const SlabSettings& settings,
                               const std::function<void(const scene::SceneSurface&)>& check_surface = {},
                               const MeshBodyBuilder& mesh_body = {});

// How the slab's settings analyse any body (modes, cache, progress, band).
ModalSettings modalSettings(const SlabSettings& settings);
AnalysisOptions analysisOptions(const SlabSettings& settings);
AudibleOptions audibleOptions(const SlabSettings& settings);

// The pen's own modes (device.pen, a cylinder: penBody), analysed as the slab is; struck at its tip.
struct PenSound {
  TetMesh mesh;
  AudibleModes modes;
  int tip_node = 0;
  double tilt_deg = 30.0;
};
PenSound buildPenSound(const scene::Scene& scene, const SlabSettings& settings);

// The scene's surface roughness as the micro level reads it (amplitude 0: none).
RoughnessOptions sceneRoughness(const scene::Scene& scene);

}  // namespace thx::audio
