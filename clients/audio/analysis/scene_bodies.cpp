#include "clients/audio/analysis/scene_bodies.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thx::audio {
namespace {

int cellsAlong(double edge, double shortest) { return std::max(1, int(std::lround(edge / shortest))); }

}  // namespace

SceneBody slabBody(const scene::Scene& scene, const SceneMeshOptions& o) {
  const scene::Surface& s = scene.surface;
  const double thickness = o.slab_thickness_m.value_or(s.thickness_m);
  const bool clamp = o.clamp_slab.value_or(s.held == scene::SlabSupport::ClampedEdges);
  return {slabMesh("surface", s.size_m.x(), s.size_m.y(), thickness, {o.slab_cells, o.slab_cells, o.slab_layers}, o.order, clamp),
          s.material, ""};
}

SceneBody penBody(const scene::Scene& scene, ElementOrder order) {
  const scene::Pen& p = scene.device.pen;
  // 2 x 2 cells across (an even count, so the axis is a grid line and the tip a node).
  return {cylinderMesh("pen", p.radius_m, p.length_m, 2, cellsAlong(p.length_m, p.radius_m), order), p.material, ""};
}

int penTipNode(const TetMesh& pen) {
  double low = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& x : pen.nodes) low = std::min(low, x.z());
  int best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t n = 0; n < pen.nodes.size(); ++n) {
    const Eigen::Vector3d& x = pen.nodes[n];
    const double d = x.head<2>().squaredNorm() + (x.z() - low) * (x.z() - low);
    if (d < best_d) best_d = d, best = int(n);
  }
  return best;
}

std::vector<SceneBody> sceneBodies(const scene::Scene& scene, const SceneMeshOptions& o) {
  std::vector<SceneBody> bodies;
  bodies.push_back(slabBody(scene, o));
  for (const scene::SceneObject& obj : scene.objects) {
    if (obj.fixed) continue;
    SceneBody b{{}, obj.material, ""};
    switch (obj.shape) {
      case scene::Shape::Sphere:
        b.mesh = sphereMesh(obj.name, obj.radius_m, kSphereCells, o.order);
        break;
      case scene::Shape::Box: {
        const double h = obj.size_m.minCoeff() / kBoxCellsShortest;
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
  if (o.pen) bodies.push_back(penBody(scene, o.order));
  return bodies;
}

}  // namespace thx::audio
