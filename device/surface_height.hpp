#pragma once
// SurfaceHeight: the height of a curved surface under the simulated hand, for its script
// (hand_script.hpp). The hand script's steps are in the surface pose's frame (the script frame:
// x, y across, z up, the push along -z); a height source tells it where the surface is under a
// script point, so that a press or a stroke lands on a bowl, a vase or a sphere as on the plane.
//
// Seen from above: heightAt(x, y) is the local z where a vertical line coming down from above the
// surface (from above top()) first meets it, the surface's outward face; top() is the highest
// local z the surface reaches (the hand hovers above it between contact steps, so its transits
// never cut through the surface).
//
// device/ knows no meshes: the server implements it over a triangle mesh
// (server/mesh_surface_height.hpp); tests implement analytic ones.
//
// Real-time contract: heightAt() and top() are called from the device's integration loop (every
// integration step while the hand is in contact, SimPhantomConfig::surface_height): no
// allocation, no locks, no exceptions, no logging; bounded time. Both must be safe to call from
// one thread while nothing modifies the source.
#include <Eigen/Core>

namespace thx::dev {

class SurfaceHeight {
 public:
  virtual ~SurfaceHeight() = default;

  // The height (local z, metres) of the surface under the script point `xy_m` seen from above,
  // in `z_m`; false, with `z_m` untouched, when nothing is under it.
  virtual bool heightAt(const Eigen::Vector2d& xy_m, double& z_m) const = 0;
  // The highest local z of the surface (metres), finite.
  virtual double top() const = 0;
};

}  // namespace thx::dev
