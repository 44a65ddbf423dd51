#pragma once
// MeshSurfaceHeight: the simulated hand's surface heights (device/surface_height.hpp) over a
// triangle mesh, so that the hand's script presses and strokes on a curved mesh (a sphere, a bowl,
// a vase) as on the plane.
//
// Frames: the mesh (and its hierarchy) is in its own frame; `mesh_to_script` places it in the
// script's frame (the surface pose's: x, y across, z up, SimPhantomConfig::plane_to_world). For a
// mesh placed in the world by mesh_to_world and a script placed by plane_to_world, pass
// plane_to_world.inverse() * mesh_to_world.
//
// heightAt(x, y): the segment from (x, y, top() + kMarginM) down to (x, y, bottom() - kMarginM)
// in the script's frame, carried into the mesh's frame, and its first FRONT-face entry
// (TriangleBvh::firstEntry): the local z of the outward face seen from above; false where the
// segment enters no face (off the mesh's footprint, or a wall seen edge-on). Inside a bowl that is
// the inside's floor, under a sphere its upper cap. top(): the highest local z of the mesh's
// vertices (computed once).
//
// Real-time safe: heightAt() is one BVH query (no allocation, no lock, no exception). Built before
// the device runs; the hierarchy (and its mesh) must outlive it.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "device/surface_height.hpp"
#include "server/triangle_bvh.hpp"

namespace thx::srv {

class MeshSurfaceHeight final : public dev::SurfaceHeight {
 public:
  // How far above the top and below the bottom the vertical query segment starts and ends.
  static constexpr double kMarginM = 0.01;

  // Throws thx::Error (Config) if mesh_to_script is not a finite rigid transform.
  MeshSurfaceHeight(const TriangleBvh& bvh, const Eigen::Isometry3d& mesh_to_script);

  bool heightAt(const Eigen::Vector2d& xy_m, double& z_m) const override;
  double top() const override { return top_m_; }
  double bottom() const { return bottom_m_; }  // the lowest local z of the mesh's vertices

 private:
  const TriangleBvh* bvh_;
  Eigen::Isometry3d script_to_mesh_;
  double top_m_ = 0.0;
  double bottom_m_ = 0.0;
};

}  // namespace thx::srv
