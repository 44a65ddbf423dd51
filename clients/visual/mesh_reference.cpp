#include "clients/visual/mesh_reference.hpp"

#include <algorithm>
#include <cmath>

namespace thx::visual {

MeshReference::MeshReference(const MeshSurface& surface)
    : surface_((checkMeshSurface(surface), surface)),
      caster_(*surface.mesh),
      tangent_plane_(surface.tangentPlane()),
      world_to_mesh_(surface.mesh_to_world.inverse()) {}

std::optional<ReferenceHit> MeshReference::hit(const Ray& ray_world, bool relief, const ReferenceLight& light) const {
  const Eigen::Vector3d o = world_to_mesh_ * ray_world.origin, v = world_to_mesh_.linear() * ray_world.direction;
  const std::optional<MeshRayHit> h = caster_.firstHit(o, v);
  if (!h) return std::nullopt;
  const mesh::SurfaceFrame f = mesh::frameAt(*surface_.mesh, h->triangle, h->barycentric, mesh::FrameMode::Interpolated);
  const auto tangential = [&](const Eigen::Vector3d& d) {
    return Eigen::Vector3d(d.dot(f.tangent), d.dot(f.bitangent), d.dot(f.normal));
  };
  const Eigen::Vector3d l = tangential(light.towards_light_local);
  // The pixel's tangent plane with the texture at the face's own scale, its normals turned to the
  // slopes as laid there (as the haptic chart does); whole tiles off change nothing of a wrapped
  // texture.
  const tex::TexturedSurface chart = surface_.chartAt(mesh::metresPerUv(*surface_.mesh, h->triangle, f));
  const Eigen::Vector2d scale = chart.mapping().size_m;
  const Eigen::Vector2d uv = f.uv - f.uv.array().floor().matrix();
  const Eigen::Vector3d entry((uv.x() - 0.5) * scale.x(), (uv.y() - 0.5) * scale.y(), 0.0);

  ReferenceHit r;
  r.p_local = entry;
  if (relief && surface_.usesRelief()) {
    // The shader's march: xy moves by v.xy / down per metre of depth, down at least 0.02 (a
    // grazing view of the tangent plane, or one from behind it at a silhouette).
    const Eigen::Vector3d vt = tangential(v);
    const Eigen::Vector3d dir(vt.x(), vt.y(), -std::max(-vt.z(), 0.02));
    const double max_depth = surface_.map->maxDepth();
    const Eigen::Vector3d exit = entry + dir * (max_depth / -dir.z());
    const std::optional<double> crossing = firstReliefCrossing(chart, entry, exit);
    r.p_local = entry + (exit - entry) * crossing.value_or(1.0);
    // As the plane's reference: from just above the hit until the light ray leaves the relief.
    const Eigen::Vector3d from = r.p_local + l * (max_depth * 1e-4);
    if (light.shadows && l.z() > 0 && from.z() < 0) {
      const Eigen::Vector3d to = r.p_local + l * (-r.p_local.z() / l.z());
      r.shadowed = firstReliefCrossing(chart, from, to).has_value();
    }
  }
  const tex::SurfacePoint sp = chart.at(r.p_local.x(), r.p_local.y());
  r.uv = sp.uv;
  r.texel = tex::texelOf(*surface_.map, sp.uv, tex::Address::Wrap);
  // n_t . l_t = (n.x T + n.y B + n.z N) . l: the frame is orthonormal.
  r.intensity = r.shadowed ? 0.0 : std::max(0.0, sp.n_local.dot(l));
  return r;
}

}  // namespace thx::visual
