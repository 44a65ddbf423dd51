#include "clients/audio/analysis/scene_mesh_body.hpp"

#include <algorithm>

#include "clients/audio/analysis/surface_tetrahedra.hpp"
#include "scenes/scene_mesh.hpp"

namespace thx::audio {

MeshSurfaceBody meshSurfaceBody(const scene::Scene& scene, ElementOrder order) {
  scene::Scene sounded = scene;
  scene::MeshSource& source = *sounded.surface.mesh;
  if (source.kind == scene::MeshSource::Kind::Generator) source.segments = std::min(source.segments, kSoundSegments);
  const scene::SceneMesh built = scene::buildSceneMesh(sounded);
  TetrahedraSettings settings;
  settings.order = order;
  MeshSurfaceBody out;
  out.body.mesh = tetrahedraOfSurface("surface (" + scene.source + ")", built.mesh, settings);
  out.body.mesh.name = "surface";
  out.body.material = scene.surface.material;
  out.mesh_to_world = built.mesh_to_world;
  out.surface_triangles = built.mesh.triangles.size();
  if (source.kind == scene::MeshSource::Kind::Generator && source.segments < scene.surface.mesh->segments)
    out.body.note = "sounded at " + std::to_string(source.segments) + " segments (the scene's mesh: " +
                    std::to_string(scene.surface.mesh->segments) + ")";
  return out;
}

}  // namespace thx::audio
