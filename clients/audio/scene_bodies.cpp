#include "clients/audio/scene_bodies.hpp"

#include <algorithm>
#include <cmath>

namespace thx::audio {
namespace {

int cellsAlong(double edge, double shortest) { return std::max(1, int(std::lround(edge / shortest))); }

}  // namespace

std::vector<SceneBody> sceneBodies(const scene::Scene& scene, const SceneMeshOptions& o) {
  std::vector<SceneBody> bodies;
  const scene::Surface& s = scene.surface;
  bodies.push_back({slabMesh("surface", s.size_m.x(), s.size_m.y(), o.slab_thickness_m,
                             {o.slab_cells, o.slab_cells, 1}, o.order, o.clamp_slab),
                    s.material, ""});
  for (const scene::SceneObject& obj : scene.objects) {
    if (obj.fixed) continue;
    SceneBody b{{}, obj.material, ""};
    switch (obj.shape) {
      case scene::Shape::Sphere:
        b.mesh = sphereMesh(obj.name, obj.radius_m, 4, o.order);
        break;
      case scene::Shape::Box: {
        const double h = obj.size_m.minCoeff();
        b.mesh = boxMesh(obj.name, obj.size_m,
                         {cellsAlong(obj.size_m.x(), h), cellsAlong(obj.size_m.y(), h), cellsAlong(obj.size_m.z(), h)},
                         o.order);
        break;
      }
      case scene::Shape::Cylinder:
        b.mesh = cylinderMesh(obj.name, obj.radius_m, obj.length_m, 2, cellsAlong(obj.length_m, obj.radius_m), o.order);
        break;
      case scene::Shape::Capsule: {
        const double length = obj.length_m + 2 * obj.radius_m;
        b.mesh = cylinderMesh(obj.name, obj.radius_m, length, 2, cellsAlong(length, obj.radius_m), o.order);
        b.note = "capsule meshed as a cylinder of its overall length";
        break;
      }
    }
    bodies.push_back(std::move(b));
  }
  return bodies;
}

}  // namespace thx::audio
