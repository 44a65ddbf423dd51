#pragma once
// Haptic rendering of a textured triangle mesh (issue 28): the texture renderer of the plane
// (proxy_renderer.hpp, with its crease handling, sided ridges and recovery rule) carried onto any
// curved surface through the mesh's interpolated tangent frames (meshes/textured_mesh.hpp).
//
// One tick, in the mesh's frame:
//   1. geometry: the god object on the flat triangles (mesh_god_object.hpp: swept, never through
//      a face, up to three faces held at an inside corner) finds the faces that hold the pen. A
//      thin plate cannot be popped through: the faces are on the side the pen came from. A tip
//      just outside the flat triangles but under the smooth surface they stand for (Phong's
//      triangles bulge out by up to `bulge()`) is held by the nearest face.
//   2. where on the smooth surface: the anchor, the point whose interpolated normal runs through
//      the texture's proxy of the last tick (the tip when contact begins): a few fixed-point steps
//      from the held face, walking onto the faces that continue it smoothly. The god object's own
//      proxy jumps at a convex edge (by depth x tan of the edge's angle); the anchor does not,
//      because the frames are continuous.
//   3. texture, one held face (a smooth surface, the common case): a chart, the plane tangent to
//      the surface at the anchor with the texture laid on it at the mesh's local scale (metres per
//      uv along the tangent and bitangent), follows the contact; the plane renderer renders the
//      texture on it with its state carried from the last tick's chart (ProxyRenderer::moveFrame).
//      The texel planes it holds at a groove's floor or a ridge span a few texels, where the
//      chart and the curved surface agree to (texel)^2 / (2 x radius of curvature).
//      Faces held at a gentle concave edge (within kSmoothNeighbourCos: the inside of a bowl)
//      are one smooth surface and rendered so. Several held faces at a crease (an inside
//      corner of the mesh): each face's textured plane at the
//      anchor (the sampled normal turned into the face's frame, through the surface point moved
//      in by the relief depth) and the tip pulled to the point closest to it outside all of them;
//      the chart's renderer starts afresh when one face holds again.
//   Without a texture: the smooth surface's plane at the anchor, per held face.
// FrameMode: the vertex frames interpolated, the point on Phong's curved triangle (the default: the
// smooth surface the normals describe), or interpolated on the flat triangle, or the face's own
// frame (CHAI3D 3.3's: the frame jumps at every edge; a baseline for the benchmark).
//
// Real-time safe: render() allocates nothing, takes no lock; its work is the god object's bounded
// sweeps (from the leaves around the pen, gathered ahead of it a bounded step per tick:
// local_triangle_set.hpp), a bounded walk across edges (kAnchorSteps x kMaxHops faces) and the plane renderer's
// tick. Built once before the servo runs (the constructor allocates the edge table and measures
// Phong's bulge, in time linear in the triangles). The mesh, hierarchy and map must outlive it.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

#include "meshes/textured_mesh.hpp"
#include "server/local_triangle_set.hpp"
#include "server/mesh_god_object.hpp"
#include "server/proxy_renderer.hpp"
#include "server/triangle_bvh.hpp"
#include "textures/sampling.hpp"
#include "textures/texture_map.hpp"
#include "textures/textured_surface.hpp"

namespace thx::srv {

struct MeshTexture {
  const tex::TextureMap* map = nullptr;  // nullptr: the smooth (shaded) surface, no texture
  tex::SampleOptions sampling;
  bool use_relief = false;  // read the map's depth as a displacement along the normal
  // The texture tile (metres per uv) the map's normals were made for (the scene's surface.size):
  // where the mesh's uv lays the texture at another local scale, its normals are turned to match
  // the depth as laid there (TexturedSurface::setNormalsMadeFor). Zero: taken as they are.
  Eigen::Vector2d normals_made_for_m = Eigen::Vector2d::Zero();
  // The map's slope steps (textures/texel_slope_steps.hpp), outliving the renderer: where they show
  // a texel's neighbours within the crease angle, the chart's renderer does not read them. nullptr:
  // it always reads them (the same forces, more work).
  const tex::TexelSlopeSteps* slope_steps = nullptr;
};

// Where the last tick's anchor was (for the contact messages).
struct MeshContact {
  bool valid = false;
  std::uint32_t triangle = 0;
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
  mesh::SurfaceFrame frame;  // mesh frame
};

class TexturedMeshRenderer {
 public:
  // `bvh` must be built over mesh.positions and mesh.triangles (the renderer reads the corners
  // there, where the sweeps do). `config` as for the plane renderer (stiffness, damping, crease
  // handling and its angle, sided ridges, recovery; not the paper's loop).
  TexturedMeshRenderer(const mesh::TexturedMesh& mesh, const TriangleBvh& bvh, const MeshTexture& texture,
                       const Eigen::Isometry3d& mesh_to_world, const RendererConfig& config,
                       mesh::FrameMode frames = mesh::FrameMode::InterpolatedPhong);
  TexturedMeshRenderer(const TexturedMeshRenderer&) = delete;  // the chart renderer points at chart_
  TexturedMeshRenderer& operator=(const TexturedMeshRenderer&) = delete;

  RenderOutput render(const Eigen::Vector3d& tip_world, const Eigen::Vector3d& v_world);
  // render() in two halves, as ProxyRenderer's (proxy_renderer.hpp): renderForce() fills the
  // force and what the device and the servo act on; describeContact() then fills where on the
  // mesh the contact is (the plane renderer's description on the chart, the triangle, barycentric
  // coordinates and smooth frame at the anchor). The servo writes the force in between.
  RenderOutput renderForce(const Eigen::Vector3d& tip_world, const Eigen::Vector3d& v_world);
  void describeContact(RenderOutput& out);
  // The work a tick does for the ticks after it, not for its own force: moving the gathering of
  // the next region on (local_triangle_set.hpp) and asking the memory for the faces round the
  // anchor's, where the next anchor walks. The servo calls it after the force is written, in the
  // slack before its next reading, so it is not between a reading and its force (docs/meshes.md,
  // "Render cost"). Without the call render() does it first thing, and the forces are the same
  // either way, to the bit. Real-time safe: bounded (kNodesPerTick nodes, three faces).
  void prepareNextTick();
  void reset();  // forget the proxy: the next tick's tip is the proxy (call it with the tip outside)

  const RendererConfig& config() const { return config_; }
  const MeshContact& lastContact() const { return contact_; }
  // The god object's sweeps from the leaves around the pen (local_triangle_set.hpp; the default)
  // or from the hierarchy every time: the same answers, for tests and benchmarks.
  void useLocalSet(bool on) { use_local_ = on; }
  const LocalTriangleSet& localSet() const { return local_; }
  int lastSweeps() const { return last_sweeps_; }
  // How far Phong's triangles rise above the flat ones at most (0 in the other frame modes).
  double bulge() const { return bulge_m_; }

 private:
  // Steps of the anchor's fixed point, from last tick's anchor: each shrinks the foot's motion
  // 10 to 100 times on the benchmark's sphere (0.1-10 um, then 1-100 nm, then 0.01-10 nm); it stops
  // when the foot moves less than the tolerance: 10 nm, far below a texel and the device's
  // resolution, 6e-6 N at 600 N/m, and a turn of the chart's normal of 10 nm / radius (3e-7 rad
  // on a 32 mm sphere). At 1e-10 m three ticks in four ran all four steps (docs/meshes.md).
  static constexpr int kAnchorSteps = 4;
  static constexpr double kAnchorToleranceM = 1e-8;
  // Faces crossed at most per walk (locate): a tick's motion crosses one or two.
  static constexpr int kMaxHops = 8;
  // Faces within this angle continue each other smoothly (meshes/textured_mesh.hpp's default
  // crease angle, 60 degrees: their vertex frames are shared).
  static constexpr double kSmoothNeighbourCos = 0.5;

  // The anchor for `from` (mesh frame), starting at `previous` (last tick's anchor) or else on the
  // held face `held` at the point nearest `start`.
  MeshContact anchor(std::uint32_t held, const MeshContact* previous, const Eigen::Vector3d& start,
                     const Eigen::Vector3d& from) const;
  // The face and barycentric coordinates of the point x near face `triangle` (updated in place),
  // walking across edges only onto faces that continue `held` smoothly.
  void locate(const Eigen::Vector3d& x, std::uint32_t held, std::uint32_t& triangle, Eigen::Vector3d& barycentric) const;
  // The textured (or smooth) plane at an anchor; the sampled normal and relief depth.
  Halfspace planeAt(const MeshContact& at, Eigen::Vector3d& n_sampled, double& relief_depth) const;
  // The held faces' normals all within kSmoothNeighbourCos of each other: one smooth surface.
  bool smoothlyJoined(const std::uint32_t* held, int count) const;
  // Metres per uv along the anchor's tangent and bitangent (its face's texture mapping).
  Eigen::Vector2d localScale(const MeshContact& at) const;
  // The chart at an anchor: the tangent plane with the texture at the face's local scale.
  tex::PlaneMapping chartAt(const MeshContact& at) const;
  // The chart at `at` made the plane renderer's surface, and its force there.
  RenderOutput renderOnChart(const MeshContact& at, const Eigen::Vector3d& tip, const Eigen::Vector3d& v);
  RenderOutput renderPlanes(const std::uint32_t* held, int count, const Eigen::Vector3d& from, const Eigen::Vector3d& tip,
                            const Eigen::Vector3d& v);
  void fillContact(RenderOutput& out, const MeshContact& at, const Eigen::Vector3d& n_sampled, double relief) const;
  // Where on the mesh (triangle, barycentric) and its smooth frame there, in the mesh's frame.
  void fillPlace(RenderOutput& out, const MeshContact& at) const;

  const mesh::TexturedMesh* mesh_;
  const TriangleBvh* bvh_;
  MeshTexture texture_;
  Eigen::Isometry3d mesh_to_world_;
  Eigen::Isometry3d world_to_mesh_;
  RendererConfig config_;
  mesh::FrameMode frames_;
  double bulge_m_ = 0.0;

  bool have_proxy_ = false;
  Eigen::Vector3d proxy_ = Eigen::Vector3d::Zero();          // the god object's, on the flat faces
  bool have_texture_proxy_ = false;
  Eigen::Vector3d texture_proxy_ = Eigen::Vector3d::Zero();  // the rendered proxy of the last tick
  std::vector<mesh::Triangle> neighbours_;  // mesh::triangleNeighbours: the walk's edges
  tex::TexturedSurface chart_;                   // the plane renderer's surface ...
  std::optional<ProxyRenderer> chart_renderer_;  // ... and the renderer on it (textured meshes only)
  bool chart_valid_ = false;  // chart_renderer_'s state belongs to chart_ (one face held last tick)
  MeshContact contact_;
  int last_sweeps_ = 0;
  LocalTriangleSet local_;
  bool use_local_ = true;
  bool next_tick_pending_ = false;  // renderForce() ran since the last prepareNextTick()
  // How the last renderForce() went, for describeContact(): the chart's renderer describes the
  // contact (Chart); renderPlanes() or no held face has described it already, in the mesh's frame
  // (Planes); a non-finite tip, in the world's (NonFinite).
  enum class Path { Chart, Planes, NonFinite };
  Path last_path_ = Path::NonFinite;
};

}  // namespace thx::srv
