#pragma once
// What a textured mesh's images should be (issue 28), on the CPU, for the tests and the
// benchmark's image error; cpu_reference.hpp does the same for the plane.
//
// Per pixel: the first front face along camera.pixelRay() (MeshRayCaster), the frame at that
// point interpolated as the shader interpolates it (mesh::frameAt, FrameMode::Interpolated: the
// flat triangle's point, the vertex frames barycentrically, no Phong), and then the plane's
// reference in that point's tangent plane (MeshSurface::chartAt: x along the tangent, y along the
// bitangent, z along the normal, uv scaled by the face's metres per uv, the normals' slopes turned
// from the stated tile to that scale, as the haptic chart): the textures library's sample there
// turned into the mesh frame (n.x T + n.y B + n.z N, so intensity = max(n . l, 0)); for relief the
// view ray's exact first crossing of the bilinear depth field (firstReliefCrossing) below that
// plane, which is the shader's tangent-space march solved exactly, and the exact shadow ray
// towards the light from the hit.
#include <optional>

#include "clients/visual/camera.hpp"
#include "clients/visual/cpu_reference.hpp"
#include "clients/visual/mesh_ray_caster.hpp"
#include "clients/visual/mesh_surface.hpp"

namespace thx::visual {

class MeshReference {
 public:
  explicit MeshReference(const MeshSurface& surface);  // builds the ray caster; the mesh must outlive this

  // `light.towards_light_local` is in the MESH frame. The hit's p_local is in the tangent plane
  // of the pixel's mesh point (z = -depth below it); uv and texel are the texture's.
  std::optional<ReferenceHit> hit(const Ray& ray_world, bool relief, const ReferenceLight& light) const;

  const MeshSurface& surface() const { return surface_; }
  // The texture as image_error.hpp's comparison reads it (the map, wrapped; mesh_image_error.hpp).
  const tex::TexturedSurface& tangentPlane() const { return tangent_plane_; }

 private:
  MeshSurface surface_;
  MeshRayCaster caster_;
  tex::TexturedSurface tangent_plane_;
  Eigen::Isometry3d world_to_mesh_;
};

}  // namespace thx::visual
