#pragma once
// Haptic rendering of a triangle mesh by a god object (Zilles & Salisbury 1995): the proxy is a
// point that never enters the surface; each tick it moves toward the device tip as far as the
// mesh lets it, and a spring-damper pulls the tip toward it. This is the renderer the textures
// replace: the relief displaced as an N x N mesh (triangle_mesh.hpp), held to the same force-error
// benchmark as the texture renderers (docs/benchmarks.md §2c).
//
// One tick, from the last proxy P (outside the surface) toward the tip H, with no constraint:
//   1. sweep P -> goal (first goal: H) through the BVH (triangle_bvh.hpp); no entry: P = goal, done.
//   2. an entry into triangle T: P stops just before it (kStandoffM back along the sweep), T's
//      plane becomes a constraint, and the goal becomes the point closest to H on the outside of
//      every constraint plane: the Lagrange-multiplier solve of up to three active planes
//      (halfspace_projection.hpp; a plane whose multiplier would pull the proxy inward is dropped,
//      so the proxy slides off a face the tip has left). Back to 1 with the constraints' own
//      triangles skipped, at most kMaxSweeps times; a fourth plane (a corner) keeps P where it stopped.
// The constraint planes are held kStandoffM outside their triangles, so the proxy ends every
// tick strictly outside and the next tick's sweep sees every face it could cross: a sweep across
// edges and vertices never passes through the surface. Beyond a convex edge the goal may lie on
// the extended plane of the face it left (above the surface); the next tick's sweep from there
// drops it back onto the surface.
// Constraints are found afresh each tick (the proxy remembers only its position), as in the
// original; no recovery rule (the texture renderers' plane-change ramp has no plane to change).
//
// Real-time safe: render() allocates nothing, takes no lock, and its work is bounded by
// kMaxSweeps BVH queries. The BVH (and its mesh) must outlive the renderer.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>

#include "server/local_triangle_set.hpp"
#include "server/proxy_renderer.hpp"
#include "server/triangle_bvh.hpp"
#include "textures/plane_mapping.hpp"

namespace thx::srv {

inline constexpr int kGodObjectMaxSweeps = 6;
inline constexpr int kGodObjectMaxConstraints = 3;
inline constexpr double kGodObjectStandoffM = 1e-9;  // 6e-7 N at 600 N/m: far below any force we resolve

// One tick of the god object (steps 1-2 above), in the mesh's frame: from the last proxy toward the
// tip. The renderer of textured meshes (textured_mesh_renderer.hpp) takes the same step and reads
// the constraint triangles to shade and texture them.
struct GodObjectStep {
  Eigen::Vector3d proxy = Eigen::Vector3d::Zero();
  std::array<Halfspace, kMaxHalfspaces> planes{};  // [0, count): the constraints, kStandoffM outside
  std::array<std::uint32_t, kGodObjectMaxConstraints> triangles{};  // their triangles
  int count = 0;
  int sweeps = 0;
};
// With `local`, every sweep is asked of it (the same answers, local_triangle_set.hpp).
GodObjectStep moveGodObject(const TriangleBvh& bvh, const Eigen::Vector3d& proxy, const Eigen::Vector3d& tip,
                            const LocalTriangleSet* local = nullptr);

class MeshGodObject {
 public:
  static constexpr int kMaxSweeps = kGodObjectMaxSweeps;
  static constexpr int kMaxConstraints = kGodObjectMaxConstraints;
  static constexpr double kStandoffM = kGodObjectStandoffM;

  // The mesh is in `mapping`'s plane frame. Only stiffness and damping of `config` apply.
  MeshGodObject(const TriangleBvh& bvh, const tex::PlaneMapping& mapping, const RendererConfig& config);

  // The same output as the texture renderers where it has a meaning: force, proxy, contact,
  // depth, and the constraint planes (world frame) in planes[0..num_planes).
  RenderOutput render(const Eigen::Vector3d& tip_world, const Eigen::Vector3d& v_world);
  void reset();  // forget the proxy: the next tick's tip is the proxy (call it with the tip outside)

  const RendererConfig& config() const { return config_; }
  const Eigen::Vector3d& proxyLocal() const { return proxy_; }
  // Sweeps the last tick took (1 = a free move or a single stop); for tests and the benchmark.
  int lastSweeps() const { return last_sweeps_; }

 private:
  const TriangleBvh* bvh_;
  RendererConfig config_;
  Eigen::Isometry3d plane_to_world_;
  Eigen::Isometry3d world_to_plane_;
  bool have_proxy_ = false;
  Eigen::Vector3d proxy_ = Eigen::Vector3d::Zero();
  int last_sweeps_ = 0;
};

}  // namespace thx::srv
