#pragma once
// What the images should be, computed on the CPU from the same TexturedSurface every sense uses,
// for the reference tests and the benchmark's image error.
//
//  - Normal mapping: the ray meets the plane z = 0; the normal there is the library's bilinear
//    sample (renormalised); intensity = max(n_s . l, 0).
//  - Relief: the surface is the BILINEAR depth field the haptic renderer feels
//    (TexturedSurface::at: z = -depth(u, v), depth interpolated between texel centres), not
//    flat-topped texels. The ray is intersected exactly: the texel walk (tex::walkTexels) lists
//    the cells between texel centres that the ray's footprint crosses, in order, and in each the
//    ray-vs-bilinear-patch equation (a quadratic in the ray parameter) is solved in closed form.
//    Shading uses the library's normal at the hit; a pixel is shadowed when the exact ray from
//    the hit towards the light meets the surface before leaving the relief.
#include <Eigen/Core>
#include <optional>

#include "clients/visual/camera.hpp"
#include "textures/textured_surface.hpp"

namespace thx::visual {

struct ReferenceHit {
  Eigen::Vector3d p_local;  // on the surface (z = -depth; 0 for normal mapping)
  tex::TexCoord uv;
  tex::TexelIndex texel;    // the texel containing uv (the map's address mode)
  double intensity = 0.0;   // max(n . l, 0), 0 when shadowed
  bool shadowed = false;
};

struct ReferenceLight {
  Eigen::Vector3d towards_light_local = Eigen::Vector3d::UnitZ();  // unit
  bool shadows = true;  // relief only
};

// The point where the ray first reaches the surface along segment a -> b (plane-local), as a
// fraction of the segment in [0, 1]; nullopt when it stays above. Relief surfaces only.
std::optional<double> firstReliefCrossing(const tex::TexturedSurface& surface, const Eigen::Vector3d& a_local,
                                          const Eigen::Vector3d& b_local);

// nullopt when the ray misses the map's rectangle (the quad is drawn only there) or runs away from
// the plane. `relief` false = normal mapping (the plane z = 0 and the sampled normal).
std::optional<ReferenceHit> referenceHit(const tex::TexturedSurface& surface, const Ray& ray_world, bool relief,
                                         const ReferenceLight& light);

}  // namespace thx::visual
