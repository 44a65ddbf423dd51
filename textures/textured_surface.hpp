#pragma once
// A texture placed on its plane, read as the geometry it stands for: the surface height and the
// sampled normal at a plane-local point. This is what haptics, physics and sound query.
//
//  - normal map: the surface is the plane itself (height 0); only the normal varies.
//  - relief map: the surface is z = -depth(u, v), with the relief normal.
// Beyond a clamped map's border the edge texels continue: a normal map's virtual slope goes on,
// but a relief's clamped depth is flat there, so its normal is the plane's (the edge texel's
// tilted normal over a flat continuation would push objects outward forever, gaining energy).
// Real-time safe (no allocation): it holds a pointer to a map that must outlive it.
#include <Eigen/Core>
#include <cmath>

#include "textures/plane_mapping.hpp"
#include "textures/sampling.hpp"
#include "textures/texel_slope_steps.hpp"
#include "textures/texture_map.hpp"

namespace thx::tex {

// The centre of one texel read as geometry: the surface point there and the texel's own normal
// (no interpolation). Texel indices here are UNWRAPPED: neighbours of a texel near the seam keep
// consecutive indices (and centres), the data is read through the map's address mode.
struct TexelPoint {
  Eigen::Vector3d q_local = Eigen::Vector3d::Zero();
  Eigen::Vector3d n_local = Eigen::Vector3d::UnitZ();
};

struct SurfacePoint {
  double height_m = 0.0;                               // z of the surface in the plane frame (<= 0)
  Eigen::Vector3d n_local = Eigen::Vector3d::UnitZ();  // sampled normal, plane frame, unit
  TexCoord uv;
};

// A tangent-frame normal (not yet unit) whose slopes are multiplied by `scale` along x and y: the
// relief's normal when the map is laid at 1 / scale of the size its normals were made for.
inline Eigen::Vector3d scaleSlopes(const Eigen::Vector3d& n, const Eigen::Vector2d& scale) {
  return {n.x() * scale.x(), n.y() * scale.y(), n.z()};
}

class TexturedSurface {
 public:
  TexturedSurface() = default;
  // use_relief: read the map's depth as geometry (needs a relief map); false = normal-map reading.
  TexturedSurface(const TextureMap& map, const PlaneMapping& mapping, const SampleOptions& sampling, bool use_relief)
      : map_(&map),
        mapping_(mapping),
        world_to_plane_(mapping.plane_to_world.inverse()),
        sampling_(sampling),
        use_relief_(use_relief && map.isRelief()) {}

  SurfacePoint at(double x_local, double y_local) const {
    SurfacePoint p;
    p.uv = mapping_.uvOfLocal({x_local, y_local});
    const Sample s = sample(*map_, p.uv, sampling_);
    p.n_local = flatBeyondClampedEdge(p.uv.u, p.uv.v) ? Eigen::Vector3d::UnitZ()
                                                      : slopeScaled(s.normal.cast<double>()).normalized();  // float sums are off by ~1e-8
    p.height_m = use_relief_ ? -double(s.depth) : 0.0;
    return p;
  }

  // The unwrapped texel index containing continuous texel coordinate s (u x width, or
  // (1 - v) x height), clamped to +-1e9 texels so the integer conversion stays defined. A mesh's
  // contacts count their texels with it too (clients/physics_client/mesh_ground.hpp).
  static long long toIndex(double s) {
    constexpr double kLimit = 1e9;
    return (long long)std::floor(std::fmax(-kLimit, std::fmin(kLimit, s)));
  }

  // Unwrapped index of the texel containing plane-local (x, y). Coordinates beyond +-1e9 texels
  // are clamped (nothing physical lives there) so the integer conversion stays defined.
  void texelContaining(double x_local, double y_local, long long& i, long long& j) const {
    const TexCoord uv = mapping_.uvOfLocal({x_local, y_local});
    i = toIndex(uv.u * map_->width());
    j = toIndex((1.0 - uv.v) * map_->height());
  }
  TexelPoint texelPoint(long long i, long long j) const {
    const int ri = resolveIndex(i, map_->width(), sampling_.address);
    const int rj = resolveIndex(j, map_->height(), sampling_.address);
    TexelPoint p;
    p.n_local = texelNormal(i, j, ri, rj);
    p.q_local = texelCentre(i, j, ri, rj);
    return p;
  }
  // The surface point at the centre of texel (i, j) (unwrapped) without its normal: the cheap half
  // of texelPoint, for searches that read many texels and keep few.
  Eigen::Vector3d texelCentre(long long i, long long j) const {
    return texelCentre(i, j, resolveIndex(i, map_->width(), sampling_.address),
                       resolveIndex(j, map_->height(), sampling_.address));
  }
  Eigen::Vector3d texelCentre(long long i, long long j, int ri, int rj) const {
    const TexCoord centre{(double(i) + 0.5) / map_->width(), 1.0 - (double(j) + 0.5) / map_->height()};
    const Eigen::Vector2d xy = mapping_.localOfUv(centre);
    return {xy.x(), xy.y(), use_relief_ ? -double(map_->depth(ri, rj)) : 0.0};
  }

  // The normal of texel (i, j) (unwrapped), whose data sits at (ri, rj) (resolved through the
  // address mode): flat beyond a clamped relief's border.
  Eigen::Vector3d texelNormal(long long i, long long j, int ri, int rj) const {
    const bool flat = use_relief_ && sampling_.address == Address::Clamp && (ri != i || rj != j);
    return flat ? Eigen::Vector3d::UnitZ() : slopeScaled(map_->normal(ri, rj).cast<double>()).normalized();
  }

  // The map's normals were made for a texture spanning `made_for_m` (its tile on the scene,
  // docs/scenes.md); this surface lays it over mapping().size_m. Where the two differ (a mesh's
  // chart where its uv squeezes or stretches the texture, textured_mesh_renderer.hpp) the normals
  // are turned to the slopes of the relief as laid here: slope x made_for / size along each axis,
  // so the normals keep matching the depth. Off (the plane: its size is what the normals are for)
  // until called; a non-positive size turns it off.
  void setNormalsMadeFor(const Eigen::Vector2d& made_for_m) {
    rescaled_ = made_for_m.x() > 0.0 && made_for_m.y() > 0.0 && mapping_.size_m.x() > 0.0 && mapping_.size_m.y() > 0.0;
    if (rescaled_) slope_scale_ = made_for_m.cwiseQuotient(mapping_.size_m);
  }

  // The map's slope steps (texel_slope_steps.hpp), built for this surface's map and outliving the
  // surface; nullptr (the default) when none were built.
  void setSlopeSteps(const TexelSlopeSteps* steps) {
    steps_ = steps && map_ && steps->width() == map_->width() && steps->height() == map_->height() ? steps : nullptr;
  }
  const TexelSlopeSteps* slopeSteps() const { return steps_; }
  // True when every 4-neighbour of texel (i, j) (unwrapped) has a normal, as texelNormal() reads
  // it, within asin(max_sine) of texel (i, j)'s: the slope step bound times this surface's largest
  // slope scale is at most max_sine. False when it cannot be told (no steps built; a clamped map's
  // border texels, whose neighbours are read flat or repeated rather than across the edge).
  bool neighboursTurnWithin(long long i, long long j, double max_sine) const {
    if (!steps_) return false;
    int ri = 0, rj = 0;
    if (sampling_.address == Address::Clamp) {
      if (i < 1 || j < 1 || i > map_->width() - 2 || j > map_->height() - 2) return false;
      ri = int(i), rj = int(j);
    } else {
      ri = resolveIndex(i, map_->width(), Address::Wrap), rj = resolveIndex(j, map_->height(), Address::Wrap);
    }
    const double scale = rescaled_ ? slope_scale_.maxCoeff() : 1.0;
    return steps_->bound(ri, rj) * scale <= max_sine;
  }

  Eigen::Vector3d toLocal(const Eigen::Vector3d& p_world) const { return world_to_plane_ * p_world; }
  const Eigen::Isometry3d& worldToPlane() const { return world_to_plane_; }  // mapping().plane_to_world.inverse()
  Eigen::Vector3d toWorld(const Eigen::Vector3d& p_local) const { return mapping_.plane_to_world * p_local; }
  Eigen::Vector3d directionToWorld(const Eigen::Vector3d& d_local) const { return mapping_.plane_to_world.linear() * d_local; }
  Eigen::Vector3d directionToLocal(const Eigen::Vector3d& d_world) const { return world_to_plane_.linear() * d_world; }

  const TextureMap& map() const { return *map_; }
  const PlaneMapping& mapping() const { return mapping_; }
  const SampleOptions& sampling() const { return sampling_; }
  bool usesRelief() const { return use_relief_; }
  // The smaller texel side in metres: the natural length scale of the surface's detail.
  double texelSize() const {
    const Eigen::Vector2d t = mapping_.texelSize(*map_);
    return t.minCoeff();
  }

 private:
  bool flatBeyondClampedEdge(double u, double v) const {
    return use_relief_ && sampling_.address == Address::Clamp && (u < 0.0 || u > 1.0 || v < 0.0 || v > 1.0);
  }
  // A normal (not yet unit) with its slopes scaled (setNormalsMadeFor).
  Eigen::Vector3d slopeScaled(const Eigen::Vector3d& n) const { return rescaled_ ? scaleSlopes(n, slope_scale_) : n; }

  const TextureMap* map_ = nullptr;
  PlaneMapping mapping_;
  Eigen::Isometry3d world_to_plane_ = Eigen::Isometry3d::Identity();
  SampleOptions sampling_;
  bool use_relief_ = false;
  bool rescaled_ = false;
  Eigen::Vector2d slope_scale_{1.0, 1.0};
  const TexelSlopeSteps* steps_ = nullptr;
};

}  // namespace thx::tex
