#pragma once
// Haptic rendering of a textured plane by plane proxies (docs/design.md §5, Eq. 3). Runs inside the
// servo tick: no allocation, no locks, no system calls; constant time.
//
// Two modes:
//  - single plane (crease handling off; the source paper's method): project the tip onto the
//    base plane along the geometric normal, sample n_s there, build the plane through the
//    surface point (Eq. 3) and push along n_s with a spring-damper. With a relief map, contact
//    only when the tip is below the relief surface there.
//  - crease handling on: a god-object proxy. Where the texture is smooth around the proxy, one
//    plane from the interpolated normal (force shading). Where a 4-neighbour texel's normal
//    differs sharply AND the two texel planes form a concave crease (each texel centre lies
//    inside the other's half-space), the texel planes themselves are held, up to four. The proxy
//    is the point closest to the tip inside all of them (halfspace_projection.hpp). If that
//    point lands in another texel, that texel's planes are merged in (concave ones only) and the
//    projection repeated, at most kMaxMerges times, so a deep tip cannot make the proxy leap
//    over a crease. At a V-valley floor both walls are held at once and the pen rests at the
//    floor instead of bouncing between two single planes. Where the sharp neighbour forms a
//    convex crease with walls continuing on both sides (a ridge), the point takes the texel
//    plane of the side it lies on: the lower of the two texel planes at its (x, y), so the ridge
//    sits where the planes intersect, to a fraction of a texel, instead of being blended over a
//    texel by the interpolated normal (`RendererConfig::sided_ridges`, issue 12).
//    Where the surface's slope steps (textures/texel_slope_steps.hpp) show every neighbour within
//    the crease angle, the neighbours are not read: the interpolated plane is what reading them
//    would give, to the bit.
// Both: the recovery rule. If this tick's penetration differs by more than a threshold from what
// last tick's planes give for this tick's tip (a plane changed under the pen; the tip's own
// motion never counts), the previous penetration is kept and the rendered penetration moves to
// the new one over `recovery_ticks` ticks (VRPN's rule, which stock VRPN servers leave disabled).
// Contact loss with a large force ramps out the same way.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>

#include "device/haptic_device.hpp"
#include "server/halfspace_projection.hpp"
#include "textures/textured_surface.hpp"

namespace thx::srv {

struct RendererConfig {
  double stiffness_n_per_m = 600.0;
  double damping_ns_per_m = 0.0;  // along the spring direction only; never pulls the pen in
  bool crease_handling = true;
  double crease_angle_deg = 8.0;      // neighbour texels whose normals differ more form a crease
  // Convex creases (ridges: a sharp convex bend between two texels whose walls continue on both
  // sides; kRidgeContrast), with crease handling (issue 12). true: a point next to a ridge takes
  // the texel plane of the side it lies on (the lower of the two texel planes at its (x, y): the
  // ridge is where the planes meet), and on a relief, contact begins at that surface rather than
  // at the bilinear depth, which rounds a ridge down by up to slope x half a texel. false: issue
  // 3's renderer, kept for comparison (bench_force_error's "blend" rows): one plane from the
  // interpolated normal, which blends the two walls across the ridge, and a proxy entering there
  // can slide over the ridge onto the far wall.
  bool sided_ridges = true;
  int recovery_ticks = 10;            // 0 disables the recovery rule
  // A plane change is a jump of the spring force (k x the unexplained penetration change) above
  // this: a force threshold, so a deep press on a soft surface, whose long penetration vector
  // swings with every small normal change, does not count every tick as a plane change.
  double recovery_jump_n = 0.2;
  // The source paper's loop (its §4.3; server/paper_loop.hpp): the single plane is computed once
  // per graphics frame and the device renders that plane at the servo rate, so a plane is held for
  // this many ticks. 1: a new plane every tick. Only without crease handling.
  int plane_hold_ticks = 1;
};

struct RenderOutput {
  bool in_contact = false;   // a spring acts (including a recovery ramp-out)
  bool recovering = false;   // the recovery ramp is active this tick
  bool proxy_held = false;   // the proxy is held on the surface, the tip below it (else proxy = tip)
  Eigen::Vector3d force_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d proxy_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d p_proj_world = Eigen::Vector3d::Zero();  // tip projected onto the base plane
  tex::TexCoord uv;                                         // of p_proj
  tex::TexelIndex texel;
  Eigen::Vector3d n_geom_world = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d n_sampled_world = Eigen::Vector3d::UnitZ();  // at p_proj
  double depth_m = 0.0;          // rendered penetration (spring length)
  double relief_depth_m = 0.0;   // relief depth at p_proj (0 for normal maps)
  std::array<dev::PlaneProxy, dev::kMaxPlanes> planes{};  // world frame; [0] = the centre plane
  int num_planes = 0;
  unsigned active_mask = 0;       // planes touching the proxy
  double f_normal_n = 0.0;        // force along planes[0].n_world (> 0 pushes out)
  Eigen::Vector3d v_tangent_world = Eigen::Vector3d::Zero();
  // Where on the surface p_proj is: a textured mesh's triangle and barycentric coordinates (-1
  // and 0 on the plane), and the tangent frame there with n_geom_world (increasing u and v; the
  // plane's x and y axes on the plane).
  std::int32_t triangle = -1;
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
  Eigen::Vector3d tangent_world = Eigen::Vector3d::UnitX();
  Eigen::Vector3d bitangent_world = Eigen::Vector3d::UnitY();
};

class ProxyRenderer {
 public:
  ProxyRenderer(const tex::TexturedSurface& surface, const RendererConfig& config);

  RenderOutput render(const Eigen::Vector3d& tip_world, const Eigen::Vector3d& v_world);
  // render() in two halves, for a caller that writes the force in between (server/servo.cpp), so
  // that between a reading and its force is only what the force needs. renderForce() fills the
  // force and what the device and the servo act on: in_contact, recovering, proxy_held,
  // force_world, proxy_world, depth_m, planes, num_planes, active_mask, f_normal_n.
  // describeContact() then fills, for the same tick, where the tip is on the surface: p_proj_world,
  // uv, texel, the frame (n_geom, tangent, bitangent), n_sampled_world and relief_depth_m at
  // p_proj, v_tangent_world. render() is the two together, the same output to the bit.
  RenderOutput renderForce(const Eigen::Vector3d& tip_world, const Eigen::Vector3d& v_world);
  void describeContact(RenderOutput& out);
  void reset();  // forget the proxy and any recovery (e.g. after a device fault)
  // Another surface and configuration from the next render() on (a scene switch; the servo does
  // it at a tick boundary with the force ramped to zero), then reset(). Real-time safe; the
  // surface must outlive its use as with the constructor's.
  void retarget(const tex::TexturedSurface& surface, const RendererConfig& config);

  // The surface's plane frame moved (a chart that follows the contact on a curved mesh,
  // textured_mesh_renderer.hpp): what the renderer remembers in plane-local coordinates (proxy,
  // last planes, recovery) is carried into the new frame by old_to_new, and the surface's derived
  // sizes are read again. The surface object itself (same address) must already hold the new
  // mapping. Real-time safe.
  void moveFrame(const Eigen::Isometry3d& old_to_new);

  const RendererConfig& config() const { return config_; }
  const tex::TexturedSurface& surface() const { return *surface_; }

 private:
  struct LocalPlanes {
    std::array<Halfspace, kMaxHalfspaces> h{};
    std::array<Eigen::Vector3d, kMaxHalfspaces> q{};  // the surface point each plane was built through
    int count = 0;
    bool ridge = false;  // planesAround: a ridge (Bend::Ridge) borders the texel (sided_ridges)
  };
  static constexpr int kMaxMerges = 3;
  // How one 4-neighbour's texel plane meets the centre texel's: within the crease angle; a sharp
  // concave crease (both planes held); a sharp convex bend read as a ridge (sided_ridges: the
  // point takes the plane of its side); any other sharp convex bend (one interpolated plane).
  enum class Bend { Smooth, Concave, Ridge, Convex };
  // A sharp convex bend is a ridge when, on both sides, the wall continues: the next texel's
  // normal turns by at most 1 / kRidgeContrast of the bend (as normal-vector chords), or the next
  // bend is concave (the wall runs into a valley floor: a V whose walls span one or two texels).
  // A coarsely sampled smooth top spreads its bend over the texels on either side (a sine at 6.4
  // texels per period: 0.24 between the top's texels, 0.27 one texel further); a plane sampled
  // twice does not turn at all. Both sides, because one side alone is fooled by an inflection,
  // where a sine's normal barely turns (0.03 there: one side alone faceted the sine at 128²,
  // 10.8 -> 11.3 % RMS force error in bench_force_error). With the concave clause, 2 % of the
  // sine's probes at 128² (6.4 texels per period) see a ridge (10.80 -> 10.77 %); none at 256².
  static constexpr double kRidgeContrast = 5.0;
  LocalPlanes planesAround(double x, double y) const;
  // Height at plane-local (x, y) of the plane through texel point `t` (its normal has n_z > 0).
  static double planeHeightAt(const tex::TexelPoint& t, double x, double y);
  LocalPlanes singlePlaneAt(const tex::SurfacePoint& s, double x, double y) const;
  bool mergeConcave(LocalPlanes& into, const LocalPlanes& from) const;
  bool concavePair(const Halfspace& a, const Eigen::Vector3d& qa, const Halfspace& b, const Eigen::Vector3d& qb) const;
  Eigen::Vector3d applyRecovery(const Eigen::Vector3d& tip, const Eigen::Vector3d& e_target, bool& recovering);
  void derive();  // crease_cos_, smooth_sine_ from the configuration, then deriveFromSurface()
  void deriveFromSurface();  // concave_tolerance_m_ from the surface's texel size

  const tex::TexturedSurface* surface_;
  RendererConfig config_;
  double crease_cos_ = 1.0;
  double concave_tolerance_m_ = 0.0;
  double smooth_sine_ = 0.0;  // neighboursTurnWithin's bound: 0 never skips reading the neighbours

  // The last renderForce()'s tip and velocity (plane-local), and the surface point under the tip
  // if the force needed it (entering contact, the single-plane modes): describeContact() reads it
  // there rather than sampling the map again.
  Eigen::Vector3d tip_local_ = Eigen::Vector3d::Zero(), v_local_ = Eigen::Vector3d::Zero();
  bool have_at_tip_ = false;
  tex::SurfacePoint at_tip_;
  const tex::SurfacePoint& tipPoint();  // at_tip_, sampled on first use in a tick

  bool in_contact_ = false;
  Eigen::Vector3d proxy_local_ = Eigen::Vector3d::Zero();
  LocalPlanes prev_planes_;  // last tick's plane set (empty without contact): predicts this tick
  LocalPlanes prev_active_;  // of those, the ones that held the proxy
  Eigen::Vector3d e_rendered_prev_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d recovery_offset_ = Eigen::Vector3d::Zero();
  int recovery_left_ = 0;
  LocalPlanes held_plane_;  // the paper's loop: this frame's plane ...
  int held_ticks_left_ = 0;  // ... for this many more ticks
};

}  // namespace thx::srv
