#include "clients/audio/synthesis/sounding_scene.hpp"

#include "clients/audio/analysis/scene_bodies.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_frames.hpp"

namespace thx::audio {
namespace {

std::shared_ptr<const ModalBody> analysedBody(const TetMesh& mesh, const ElasticMaterial& material, const BodyOptions& o) {
  return std::make_shared<const ModalBody>(mesh, audibleModes(analyse(mesh, material, o.modal, o.analysis), material, o.audible));
}

}  // namespace

BodyOptions bodyOptions(const SlabSettings& slab, ElementOrder object_order) {
  BodyOptions bo;
  bo.slab_thickness_m = slab.thickness_m;
  bo.slab_cells = slab.cells;
  bo.slab_layers = slab.layers;
  bo.clamp_slab = slab.clamp_edges;
  bo.object_order = object_order;
  bo.modal = modalSettings(slab);
  bo.analysis = analysisOptions(slab);
  bo.audible = audibleOptions(slab);
  return bo;
}

SoundingScene soundingScene(const std::string& name, const scene::Scene& scene, bool relief, const BodyOptions& o,
                            std::shared_ptr<const ModalBody> surface,
                            std::optional<Eigen::Isometry3d> surface_mesh_to_world) {
  SoundingScene s;
  s.name = name;
  s.scene = scene;
  s.mapping = scene::planeMapping(scene.surface);
  s.relief = relief;
  s.slab_thickness_m = o.slab_thickness_m.value_or(scene.surface.thickness_m);
  if (surface) {
    s.surface = std::move(surface);
    s.surface_mesh_to_world = surface_mesh_to_world;
  } else {
    scene::requirePlaneSurface(scene, "audio-client");  // a mesh scene's surface comes from SurfaceSound
    SceneMeshOptions so;
    so.slab_thickness_m = o.slab_thickness_m;
    so.clamp_slab = o.clamp_slab;
    so.slab_cells = o.slab_cells;
    so.slab_layers = o.slab_layers;
    SceneBody slab = slabBody(scene, so);
    slab.mesh.name = "surface (" + slab.material.name + ")";
    s.surface = analysedBody(slab.mesh, slab.material, o);
  }
  SceneMeshOptions mo;
  mo.order = o.object_order;
  mo.slab_cells = mo.slab_layers = 1;  // sceneBodies' slab is not used: the surface is above
  mo.pen = false;     // the pen is not a physics body (its own modes sound in the scrape)
  const std::vector<SceneBody> bodies = sceneBodies(scene, mo);
  std::size_t next = 1;
  for (const scene::SceneObject& obj : scene.objects) {
    if (obj.fixed) {
      s.objects.push_back(nullptr);
      continue;
    }
    const SceneBody& b = bodies[next++];
    s.objects.push_back(analysedBody(b.mesh, b.material, o));
  }
  return s;
}

void setPenBody(SoundingScene& scene, const PenSound& pen) {
  if (pen.modes.size() == 0) return;
  scene.pen = std::make_shared<const ModalBody>(pen.mesh, pen.modes);
  scene.pen_tip_node = pen.tip_node;
  scene.pen_tilt_deg = pen.tilt_deg;
}

}  // namespace thx::audio
