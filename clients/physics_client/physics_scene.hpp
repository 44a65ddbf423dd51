#pragma once
// The physics client's simulation, free of LCM so tests run it directly: a scene's textured
// plane (normal or relief, as the scene says), its objects (dynamic bodies and fixed obstacles)
// and the pens, each following one device's tip (one by default; a scene of several devices has
// one per device, SimOptions::pens): kinematic bodies by default, or dynamic bodies on a virtual
// coupling to the tip for grasping (PenOptions::coupling_n_per_m). Each step reports
//  - per pen, the force its contacts put on it (scaled, translational, clamped): what goes back
//    to that pen's device as client_force_t;
//  - impacts (pairs that start touching with an approach speed) and lasting contacts (per
//    touching pair: point, normal, slip velocity, normal force, the texels entered).
// Body ids: i >= 0 = scene.objects[i]; kBodySurface = the plane; kBodyPen = a pen, every pen
// (the physics messages have one pen id; Impact::pen says which).
// A mesh scene's surface (surface.mesh) is its mesh (mesh_ground.hpp): contacts on it carry the
// texel under them through the mesh's uv, and paths follow the foot of a body's centre on it.
// SI units, world frame. Not real-time code (construction allocates; a step allocates only when
// a new pair starts touching).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "clients/physics/physics_world.hpp"
#include "clients/physics_client/mesh_ground.hpp"
#include "scenes/scene.hpp"
#include "scenes/scene_surface.hpp"
#include "textures/textured_surface.hpp"

class btRigidBody;
class btCollisionObject;

namespace thx::physclient {

inline constexpr int kBodySurface = -1;
inline constexpr int kBodyPen = -2;

enum class PenShape { None, Sphere, Capsule };

struct PenOptions {
  // A scene device with `tool: capsule` (docs/scenes.md "device.tool") gets that capsule as its pen:
  // the tool's radius and length, its tip ball centred on the device's point and its shaft along
  // the device orientation's +z (setPenOrientation), so the shaft the servo renders against the
  // texture also pushes the objects (kinematic pens only; a grasping pen stands on the tip as
  // below). false: every pen is `shape` below (physics-client's --pen-shape/-radius/-length).
  bool scene_tool = true;
  PenShape shape = PenShape::Capsule;
  double radius_m = 0.004;   // sphere radius, or the capsule's
  double length_m = 0.04;    // capsule: between the cap centres; the capsule stands on the tip
                             // along the surface's geometric normal (3-DOF device: no pen axis)
  double force_scale = 1.0;  // client force = scale x contact force on the pen
  double max_force_n = 2.0;  // |client force| clamp (hapticd refuses above its peak force)
  bool friction = true;      // include the contacts' friction impulses, not only the normal ones
  // A pen pose that jumps farther than this in one step is a teleport (first pose, reconnect):
  // no velocity is derived from it, so it cannot fling objects.
  double teleport_m = 0.02;
  double material_friction = 0.5;  // the pen's (Bullet multiplies a pair's two frictions)
  // Grasping (issue 30). 0 (default): a kinematic pen that follows the tip exactly; it pushes,
  // but its contact impulses are unbounded, so two of them squeezing a box penetrate it (590-670 N
  // measured) instead of gripping it. > 0: each pen is a dynamic body of coupling_mass_kg (no
  // gravity, no rotation: a held tip does not roll) pulled to the tip by a spring of this stiffness
  // and critical damping, touching only the dynamic objects (hapticd renders the surface; pens
  // pass through each other and the fixed obstacles, as kinematic pens do). The force sent back to
  // the device is the coupling's reaction, so a hand pushing two pens against a box's sides
  // squeezes it with what it pushes and can lift it by friction (docs/physics.md, "Grasping").
  double coupling_n_per_m = 0.0;
  double coupling_mass_kg = 0.02;
  bool coupled() const { return coupling_n_per_m > 0.0; }
};

struct SimOptions {
  PenOptions pen;
  int pens = 1;  // pen bodies (pen i follows scene device i); more: addPens()
  // The scene device each pen follows (its tool shapes the pen); when given, one pen per entry
  // and `pens` is ignored.
  std::vector<int> pen_devices;
  double impact_min_speed_m_per_s = 0.005;  // slower first touches are lasting contacts only
  phys::WorldOptions world;
};

struct BodyState {
  int id = 0;
  Eigen::Vector3d p_world = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_world = Eigen::Quaterniond::Identity();
  Eigen::Vector3d v_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_world = Eigen::Vector3d::Zero();
};

struct Impact {
  std::int64_t step = 0;
  double sim_time_s = 0.0;
  int body_a = 0, body_b = 0;  // body_b is the surface when the surface is involved
  double impulse_ns = 0.0;     // normal impulse of the impact step
  double v_approach_m_per_s = 0.0;
  Eigen::Vector3d p_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d n_world = Eigen::Vector3d::UnitZ();  // from b towards a
  bool on_surface = false;
  long long texel_i = 0, texel_j = 0;  // unwrapped, when on_surface
  int pen = -1;                        // which pen, when one body is kBodyPen
};

// One texel a surface contact's path crossed: what the paper's Eq. 5 needs at each new texel.
// The path follows the point under a's centre of mass on the plane (docs/physics.md, "Texel paths").
struct Texel {
  long long i = 0, j = 0;                              // unwrapped (TexturedSurface::texelContaining)
  double t_s = 0.0;                                    // simulated time the path entered it
  Eigen::Vector3d n_world = Eigen::Vector3d::UnitZ();  // the texel's own normal (nearest, not bilinear)
  Eigen::Vector3d v_world = Eigen::Vector3d::Zero();   // path velocity along the plane in that step
};

// One touching pair, accumulated since the last takeContacts().
struct LastingContact {
  int body_a = 0, body_b = 0;
  double mass_a_kg = 0.0;                             // 0 for a fixed obstacle or the pen
  Eigen::Vector3d p_world = Eigen::Vector3d::Zero();  // at the last step
  Eigen::Vector3d n_world = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d v_slip_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_world = Eigen::Vector3d::Zero();  // of a's centre
  double impulse_sum_ns = 0.0;                        // normal impulses over the window
  double window_s = 0.0;                              // time this pair touched in the window
  std::vector<Texel> path;                            // every texel crossed, in order (surface contacts)
  static constexpr std::size_t kMaxPath = 4096;       // longer paths drop their tail (counted)
  long long path_dropped = 0;
  double meanNormalForceN() const { return window_s > 0 ? impulse_sum_ns / window_s : 0.0; }
};

struct PenForce {
  // Contact force on the pen (N), unscaled; a coupled pen: the coupling's pull on the device
  // (spring and damper, after the step), which at rest equals the contact force on the pen.
  Eigen::Vector3d raw_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d sent_world = Eigen::Vector3d::Zero(); // scaled and clamped
  bool clamped = false;
  bool in_contact = false;
};

// A scene material as the physics world's (friction, restitution, rolling and spinning friction).
phys::BodyMaterial materialOf(const scene::Material& m);

// A ball of `radius_m` on a relief plane whose texels are coarse against it: where the relief has
// features at its texels the ball's contacts stand at texel centres (refined by a parabola through
// their neighbours), and it can jitter there (docs/physics.md, Known gaps). On a flat relief or a
// uniform slope it meets the relief between the centres since 2026-12-07 (deepestBetweenTexelCentres).
// The warning names the ball and the texel count that would do, or is empty where a texel is at
// most kCoarseTexelPerRadius of the radius.
inline constexpr double kCoarseTexelPerRadius = 0.25;
std::string coarseReliefWarning(const std::string& ball, double radius_m, const Eigen::Vector2d& texel_m,
                                const Eigen::Vector2d& surface_m);

class PhysicsScene {
 public:
  // Builds the scene's surface with scene::buildSceneSurface, smoothing included (throws
  // scene::SceneError / tex::TextureError).
  explicit PhysicsScene(const scene::Scene& scene, const SimOptions& options = {});
  ~PhysicsScene();
  PhysicsScene(const PhysicsScene&) = delete;
  PhysicsScene& operator=(const PhysicsScene&) = delete;

  // Pen bodies up to `count` (never fewer; at most client::kMaxDevices in use), added after the
  // objects as the constructor adds SimOptions::pens: call before the first step, so that a scene
  // whose pen count is known late (hapticd's hello) steps as if built with it.
  void addPens(int count);
  // The same with the scene device each pen follows: pen i follows devices[i] (a pen that followed
  // another device is made anew for this one; call before the first step).
  void addPens(const std::vector<int>& devices);
  int penCount() const { return int(pens_.size()); }
  // The orientation of pen `pen`'s device (device_state_t.q_world), for a pen along its device's
  // axis (PenOptions::scene_tool); other pens ignore it. Non-finite or zero: the last one is kept.
  void setPenOrientation(int pen, const Eigen::Quaterniond& q_world);
  // The pen's body: its shape and size, and whether it lies along its device's axis.
  struct PenBody {
    PenShape shape = PenShape::Capsule;
    double radius_m = 0.004, length_m = 0.04;
    bool along_device = false;
  };
  PenBody penBody(int pen = 0) const { return pens_.at(std::size_t(pen)).geometry; }
  // The tip of pen `pen` (default the first) for the next step (world frame). Before the first
  // call a pen is parked far above the plane and touches nothing.
  void setPenTip(const Eigen::Vector3d& tip_world) { setPenTip(0, tip_world); }
  void setPenTip(int pen, const Eigen::Vector3d& tip_world);
  // One physics step of dt_s; afterwards penForce(), impacts() and the contacts are current.
  void step(double dt_s);

  const PenForce& penForce(int pen = 0) const { return pens_.at(std::size_t(pen)).force; }
  const std::vector<Impact>& impacts() const { return impacts_; }  // this step's
  // Lasting contacts since the previous call (pairs touching in at least one step of it).
  std::vector<LastingContact> takeContacts();
  std::vector<BodyState> bodies() const;  // one per scene object, in scene order
  BodyState body(int id) const;
  Eigen::Vector3d penTip(int pen = 0) const { return pens_.at(std::size_t(pen)).tip; }

  std::int64_t steps() const { return steps_; }
  double simTime() const { return sim_time_; }
  const tex::TexturedSurface& surface() const { return scene_surface_.surface; }
  // The surface with its scene name and fingerprint, to compare with hapticd's hello_t.
  const scene::SceneSurface& sceneSurface() const { return scene_surface_; }
  const scene::Scene& scene() const { return scene_; }
  // The surface's mesh in a mesh scene; nullptr on the plane.
  const MeshGround* meshGround() const { return mesh_.get(); }
  // What the client should warn about this scene's physics: a box's normal map that leans on
  // average (scene::buildObjectTexture: its relief cannot hold the lean); on a relief plane, every
  // moving ball whose radius is small against the relief's texels (coarseReliefWarning), and on a
  // normal-mapped plane every moving ball with a bump map (it meets the relief of the plane's
  // normals).
  std::vector<std::string> warnings() const;
  phys::PhysicsWorld& world() { return *world_; }

 private:
  using PairKey = std::pair<const btCollisionObject*, const btCollisionObject*>;
  void placePens(double dt_s);
  void collectContacts(double dt_s);
  // Appends to `c` every texel the path of a (on the surface) entered in this step; on a mesh,
  // `triangle` is one the pair touches.
  void extendPath(const PairKey& key, const btCollisionObject* a, double dt_s, std::uint32_t triangle, LastingContact& c);
  struct PathPoint;
  // The walk of a mesh path from its last point (nullptr: a new touch) to `to` (extendPath's
  // part on a mesh).
  void extendMeshPath(const btCollisionObject* a, const PathPoint* from, const MeshGround::Place& to, double dt_s,
                      LastingContact& c);
  int idOf(const btCollisionObject* o) const;
  // The pen body's pose for a tip: along the plane's normal standing on it, or along the device's
  // axis with its tip ball around it.
  struct Pen;
  Eigen::Isometry3d penPoseFor(const Pen& p) const;
  PenBody bodyFor(int device) const;
  void makePen(int index, int device);  // pens_[index]'s body for `device`
  // The pen a pen body is (its user index 2), -1 for any other body.
  static int penOf(const btCollisionObject* o);

  scene::Scene scene_;
  SimOptions options_;
  scene::SceneSurface scene_surface_;
  std::unique_ptr<MeshGround> mesh_;  // before world_: the world reads its mesh and texture
  std::vector<std::unique_ptr<tex::TextureMap>> object_textures_;  // before world_: textured boxes read them
  std::vector<std::string> object_texture_warnings_;               // from building them (a leaning normal map)
  // On a normal-mapped plane with textured objects: the relief its normals integrate to, which
  // those objects meet instead of the plane (phys::PhysicsWorld::addTexturedObjectsRelief).
  std::optional<tex::TextureMap> plane_relief_map_;  // before world_: its relief plane reads it
  tex::TexturedSurface plane_relief_;
  std::unique_ptr<phys::PhysicsWorld> world_;
  btRigidBody* plane_ = nullptr;
  std::vector<btRigidBody*> objects_;
  std::vector<Eigen::Vector3d> v_before_;  // linear velocities before the step, per object

  struct Pen {
    btRigidBody* body = nullptr;  // nullptr with PenShape::None
    int device = 0;               // the scene device it follows
    PenBody geometry;
    Eigen::Vector3d tip = Eigen::Vector3d::Zero();
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();  // its device's orientation
    bool set = false, placed = false;
    PenForce force;
    // A coupled pen: where the coupling pulls its centre, and that target's velocity (this step).
    Eigen::Vector3d target = Eigen::Vector3d::Zero();
    Eigen::Vector3d v_target = Eigen::Vector3d::Zero();
  };
  // The coupling's force on a coupled pen's body (spring + critical damper towards its target).
  Eigen::Vector3d couplingForce(const Pen& p) const;
  std::vector<Pen> pens_;
  std::vector<Impact> impacts_;
  std::map<PairKey, LastingContact> contacts_;        // accumulating since takeContacts()
  struct PathPoint {
    Eigen::Vector2d xy_local = Eigen::Vector2d::Zero();  // the plane
    Eigen::Vector3d p_world = Eigen::Vector3d::Zero();   // a mesh: the foot of a's centre
    tex::TexCoord uv;
  };
  std::map<PairKey, PathPoint> last_path_point_;     // per touching surface pair: its path point a step ago
  std::map<PairKey, std::int64_t> touching_since_;    // pairs touching in the previous step
  std::int64_t steps_ = 0;
  double sim_time_ = 0.0;
};

}  // namespace thx::physclient
