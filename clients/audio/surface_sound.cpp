#include "clients/audio/surface_sound.hpp"

#include <cstdio>

#include "clients/audio/modal_analysis.hpp"
#include "clients/audio/modal_options.hpp"
#include "clients/audio/scene_bodies.hpp"
#include "scenes/scene_loader.hpp"
#include "textures/smoothing.hpp"

namespace thx::audio {

SurfaceSound buildSurfaceSound(const std::string& scene_file, const SlabSettings& o) {
  scene::Scene scene = scene::loadScene(scene_file);
  scene::SurfaceTextureOptions to;
  to.smooth = tex::smoothTexture;
  scene::SceneSurface surface = scene::buildSceneSurface(scene, to);

  const ElasticMaterial material = scene.surface.material;
  SceneMeshOptions mo;
  mo.slab_thickness_m = o.thickness_m;
  mo.clamp_slab = o.clamp_edges;
  mo.slab_cells = o.cells;
  TetMesh slab = slabBody(scene, mo).mesh;
  slab.name = "surface (" + scene.surface.material.name + ")";
  ModalSettings ms;
  ms.elastic_modes = o.modes;
  AnalysisOptions ao;
  if (!o.no_cache) ao.cache_dir = o.cache_dir ? *o.cache_dir : defaultModalCacheDir();
  if (!o.quiet) ao.progress = [](const std::string& line) { std::fprintf(stderr, "audio-client: %s\n", line.c_str()); };
  AudibleOptions audible;
  audible.sample_rate_hz = o.sample_rate_hz;
  AudibleModes modes = audibleModes(analyse(slab, material, ms, ao), material, audible);
  return SurfaceSound{std::move(scene), std::move(surface), std::move(slab), std::move(modes)};
}

}  // namespace thx::audio
