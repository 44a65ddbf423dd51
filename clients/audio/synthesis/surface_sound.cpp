#include "clients/audio/synthesis/surface_sound.hpp"

#include "scenes/scene_mesh.hpp"

#include <cstdio>

#include "clients/audio/analysis/modal_analysis.hpp"
#include "clients/audio/analysis/modal_cache.hpp"
#include "clients/audio/analysis/scene_bodies.hpp"
#include "scenes/scene_loader.hpp"
#include "textures/smoothing.hpp"

namespace thx::audio {

ModalSettings modalSettings(const SlabSettings& o) {
  ModalSettings ms;
  ms.elastic_modes = o.modes;
  return ms;
}

AnalysisOptions analysisOptions(const SlabSettings& o) {
  AnalysisOptions ao;
  if (!o.no_cache) ao.cache_dir = o.cache_dir ? *o.cache_dir : defaultModalCacheDir();
  if (!o.quiet) ao.progress = [](const std::string& line) { std::fprintf(stderr, "audio-client: %s\n", line.c_str()); };
  return ao;
}

AudibleOptions audibleOptions(const SlabSettings& o) {
  AudibleOptions audible;
  audible.sample_rate_hz = o.sample_rate_hz;
  return audible;
}

SurfaceSound buildSurfaceSound(const std::string& scene_file, const SlabSettings& o,
                               const std::function<void(const scene::SceneSurface&)>& check_surface,
                               const MeshBodyBuilder& mesh_body) {
  scene::Scene scene = scene::loadScene(scene_file);
  if (!mesh_body) scene::requirePlaneSurface(scene, "audio-client");
  scene::SurfaceTextureOptions to;
  to.smooth = tex::smoothTexture;
  scene::SceneSurface surface = scene::buildSceneSurface(scene, to);
  // hapticd's hello names a mesh scene by its texture and its mesh (as felt, at its own segments).
  if (scene.surface.mesh) surface.fingerprint = scene::meshSceneFingerprint(surface.fingerprint, scene::buildSceneMesh(scene));
  if (check_surface) check_surface(surface);

  const ElasticMaterial material = scene.surface.material;
  SceneMeshOptions mo;
  mo.slab_thickness_m = o.thickness_m;
  mo.clamp_slab = o.clamp_edges;
  mo.slab_cells = o.cells;
  mo.slab_layers = o.layers;
  std::optional<Eigen::Isometry3d> mesh_to_world;
  TetMesh slab;
  if (scene.surface.mesh) {
    MeshSurfaceBody body = mesh_body(scene);
    slab = std::move(body.body.mesh);
    mesh_to_world = body.mesh_to_world;
  } else {
    slab = slabBody(scene, mo).mesh;
  }
  slab.name = "surface (" + scene.surface.material.name + ")";
  AudibleModes modes = audibleModes(analyse(slab, material, modalSettings(o), analysisOptions(o)), material, audibleOptions(o));
  return SurfaceSound{std::move(scene), std::move(surface), std::move(slab), std::move(modes), mesh_to_world};
}

PenSound buildPenSound(const scene::Scene& scene, const SlabSettings& o) {
  SceneBody pen = penBody(scene);
  PenSound p;
  p.modes = audibleModes(analyse(pen.mesh, pen.material, modalSettings(o), analysisOptions(o)), pen.material, audibleOptions(o));
  p.tip_node = penTipNode(pen.mesh);
  p.mesh = std::move(pen.mesh);
  p.tilt_deg = scene.device.pen.tilt_deg;
  return p;
}

RoughnessOptions sceneRoughness(const scene::Scene& scene) {
  RoughnessOptions r;
  r.beta = scene.surface.roughness.beta;
  r.amplitude = scene.surface.roughness.amplitude;
  r.spacing_m = scene.surface.roughness.spacing_m;
  return r;
}

}  // namespace thx::audio
