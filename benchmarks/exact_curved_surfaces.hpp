#pragma once
// Ground truth for the textured-mesh force benchmark (bench_mesh_force, issue 28): a sphere and a
// cylinder carrying an analytic height field (sine bumps, V-grooves) on their smooth surface, the
// relief map baked from that field in the surface's tangent space, and the exact penalty force of a
// probe under the displaced surface, F = k (q - p) with q the closest point of the displaced
// surface to p. The map's normals are its depth's gradient per metre of the smooth surface (a
// relief map's own convention: its texel planes meet where its depth bends), not the displaced
// surface's 3D normals, which tilt by a further factor R / (R + z) at depth z; the truth is the
// displaced surface itself, so the difference is part of the measured error.
//
// Parameters: (X, Y) metres of arc on the smooth surface, X along the texture's u, Y along v;
// the displaced surface is base(X, Y) + z(X, Y) normal(X, Y), z = h(X, Y) - h_top <= 0 (the mesh
// is the outer envelope; the relief goes in, as the texture's depth does). One texture tile covers
// the whole surface (a sphere's tangent-space normals depend on the latitude, so a tiled map could
// not hold them): the sphere's map is 2:1 over its longitude and latitude, the cylinder's covers
// its circumference and height. Both surfaces have a radius of 0.1/pi m (a circumference of
// 0.2 m: at 1024 texels around, the plane benchmark's texel of 0.195 mm).
#include <Eigen/Core>
#include <memory>
#include <string>

#include "meshes/mesh_generators.hpp"
#include "textures/texture_map.hpp"

namespace thx::bench {

class CurvedSurface {
 public:
  virtual ~CurvedSurface() = default;
  std::string name() const { return shape_ + "+" + field_; }
  std::string description() const;
  double radius() const { return radius_m_; }
  Eigen::Vector2d extent() const { return extent_m_; }  // (X, Y) range of the one texture tile

  virtual Eigen::Vector3d base(double X, double Y) const = 0;
  virtual Eigen::Vector3d normal(double X, double Y) const = 0;  // unit, outward
  // (X, Y) of the base point under p (radial projection).
  virtual Eigen::Vector2d paramsOf(const Eigen::Vector3d& p) const = 0;
  double z(double X, double Y) const { return h(X, Y) - h_top_; }
  Eigen::Vector3d surface(double X, double Y) const { return base(X, Y) + z(X, Y) * normal(X, Y); }
  // The closest point of the displaced surface to p, a probe under it. Accurate to ~1e-10 m
  // (sine: Newton from the best point of a grid; grooves: exact along the cylinder's axis, a
  // bracketed golden-section search on each wall around it).
  virtual Eigen::Vector3d closest(const Eigen::Vector3d& p) const = 0;

  // The relief map of `width` x `height` texels (texel centres give h_top, as the plane's
  // generators do), normals (-dz/ds_t, -dz/ds_b, 1) normalised, s_t and s_b the smooth surface's
  // arc lengths along d/dX and d/dY.
  tex::TextureMap bake(int width, int height);
  // The generated mesh of about `triangles` triangles with this surface's texture mapping.
  virtual mesh::GeneratedMesh tessellate(int triangles) const = 0;
  // Where probes may go: (X, Y) within these ranges.
  virtual Eigen::Vector4d probeRange() const = 0;  // X0, X1, Y0, Y1

 protected:
  CurvedSurface(std::string shape, std::string field, double radius_m, Eigen::Vector2d extent_m)
      : shape_(std::move(shape)), field_(std::move(field)), radius_m_(radius_m), extent_m_(extent_m) {}
  virtual double h(double X, double Y) const = 0;
  Eigen::Vector3d newtonClosest(const Eigen::Vector3d& p) const;
  std::string shape_, field_;
  double radius_m_;
  Eigen::Vector2d extent_m_;
  double h_top_ = 0.0;
};

// "sine" (amplitude 0.5 mm, period 10 mm: the plane benchmark's sine) or "vgrooves" (45-degree
// walls, 2 mm period: 1 mm deep; cylinder only, grooves along the axis) on "sphere" or "cylinder".
std::unique_ptr<CurvedSurface> makeCurvedSurface(const std::string& shape, const std::string& field);

}  // namespace thx::bench
