#pragma once
// A scene as plain data: the textured surface, the haptic device (and the simulated hand's script),
// the dynamic objects and the update rates. loadScene() (scene_loader.hpp) fills every default,
// so consumers never look for a missing value. The file format is docs/scenes.md. SI units.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "scenes/device_models.hpp"
#include "scenes/materials.hpp"
#include "scenes/scene_error.hpp"
#include "textures/generators.hpp"
#include "textures/sampling.hpp"
#include "textures/texture_io.hpp"
#include "textures/texture_map.hpp"

namespace thx::scene {

// Rotation R = Rz(yaw) * Ry(pitch) * Rx(roll), angles in degrees (scene_frames.hpp converts).
struct Pose {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d rpy_deg = Eigen::Vector3d::Zero();
};

struct TextureSource {
  enum class Kind { File, Generator };
  Kind kind = Kind::Generator;
  std::string file;                // Kind::File: path, already resolved against the scene's directory
  tex::GenerateRequest generator;  // Kind::Generator: "extent" is always present in params
  SourceLocation where;            // of `texture:` in the scene file, for errors found when building it
};

// How the surface slab is held in its modal analysis (the audio client): free, or clamped at its
// four side faces.
enum class SlabSupport { Free, ClampedEdges };

// Micro-level roughness of the surface for sound (clients/audio/synthesis/fractal_roughness.hpp).
struct Roughness {
  double beta = 1.0;        // power spectrum ∝ 1/f^beta along the travelled distance
  double amplitude = 0.03;  // RMS micro force per newton of normal force
  double spacing_m = 1e-5;  // finest roughness step (wavelength 2x this)
};

// surface.mesh: the surface as a textured triangle mesh instead of the plane (docs/scenes.md,
// "surface.mesh"; built by scenes/scene_mesh.hpp). The mesh's pose places it in the surface frame,
// the surface's pose that frame in the world; the surface's size is then one texture tile in metres.
enum class MeshProjection { None, Planar, Cylindrical, Spherical };  // uv for a file without them

struct MeshSource {
  enum class Kind { File, Generator };
  Kind kind = Kind::Generator;
  std::string generator;  // Kind::Generator: a name of meshes/builtin_shapes.hpp
  double size_m = 0.05;   // Kind::Generator: the shape's radius (builtin_shapes.hpp)
  int segments = 128;     // Kind::Generator: divisions around its axis
  std::string file;       // Kind::File: OBJ, PLY, glTF 2.0 or STL, resolved against the scene's directory
  double unit_m = 1.0;    // Kind::File: metres per file unit
  MeshProjection projection = MeshProjection::None;  // Kind::File
  std::size_t max_triangles = 1'000'000;  // a mesh with more is refused
  bool closed = false;    // every edge must be shared by exactly two triangles
  // The mesh in the surface frame (the surface's pose places that frame in the world, and the
  // simulated hand's script works in it): a cylinder laid on its side, a sphere's pole turned away.
  Pose pose;
  SourceLocation where;   // of `mesh:` in the scene file, for errors found when building it
};

struct Surface {
  Eigen::Vector2d size_m{0.2, 0.2};  // the texture spans this rectangle once, centred on the pose
                                     // (on a mesh: one texture tile, metres per uv unit)
  Pose pose;
  std::optional<MeshSource> mesh;  // the surface is this mesh; none: the plane
  TextureSource texture;
  // Generator textures default to Relief. For a file, nullopt means "whatever the file holds"
  // (RGB -> normal, RGBA -> relief).
  std::optional<tex::Representation> representation;
  std::optional<double> max_depth_m;  // overrides the texture's own maximum depth (max_depth, or
                                      // max_depth_fraction × size_m.x(), the surface's width)
  tex::GreenConvention green = tex::GreenConvention::OpenGL;
  tex::SampleOptions sampling;  // bilinear + wrap by default
  Material material;
  double smoothing_sigma_texels = 0.0;  // 0 = off
  // What the audio client analyses and hears: the slab under the texture.
  double thickness_m = 0.01;
  SlabSupport held = SlabSupport::Free;
  Roughness roughness;
};

enum class DeviceType { Sim, Vrpn };

// The pen (the device's stylus) as the audio client analyses it: a cylinder of this radius and
// length, of this material, held at tilt_deg from the surface normal.
struct Pen {
  double radius_m = 0.005;
  double length_m = 0.12;
  Material material;  // plastic unless the scene says otherwise
  double tilt_deg = 30.0;
};

// device.tool (issue 30): what the servo renders the pen as. The point (the default) is the proxy of
// docs/design.md; a capsule is the stylus with extent, its tip ball's centre at the device's point
// and its shaft along the device orientation's +z, held by a 6-DOF virtual coupling
// (server/capsule_tool.hpp). The coupling's stiffness is the device's (stiffness_fraction).
enum class ToolShape { Point, Capsule };
struct Tool {
  ToolShape shape = ToolShape::Point;
  double length_m = 0.10;                 // capsule: tip ball centre to the back end
  double radius_m = 0.002;                // capsule
  double rot_stiffness_nm_per_rad = 0.5;  // capsule: capped by a 6-DOF device's limit
};

// The simulated PHANToM and the hand holding it (docs/design.md §5: integrated far above the servo
// rate so that instability stays possible).
struct SimDeviceParams {
  int integration_hz = 10000;
  double encoder_resolution_m = 2.3e-5;
  double device_mass_kg = 0.045;
  double friction_n = 0.06;
  double hand_mass_kg = 0.2;
  double hand_stiffness_n_per_m = 300.0;
  double hand_damping_ns_per_m = 3.0;
};

// Script steps for the simulated hand. Positions are surface-local (x, y) in metres; forces push
// along the surface's geometric normal, into the surface.
struct PressStep {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  double force_n = 0.0;
  double duration_s = 0.0;
};
struct StrokeStep {
  Eigen::Vector2d from_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d to_m = Eigen::Vector2d::Zero();
  double speed_m_per_s = 0.0;
  double force_n = 0.0;
};
struct PathFileStep {
  std::string path;  // resolved against the scene's directory; format in docs/scenes.md
};
struct HoldStep {
  double duration_s = 0.0;
};
// The hand moves anywhere (x, y on the surface, z above it) pushing any way (surface-local N), over
// duration_s (device/hand_script.hpp HandMove); the push stays until a contact step or the end.
struct MoveStep {
  Eigen::Vector3d to_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d push_n = Eigen::Vector3d::Zero();
  double duration_s = 0.0;
};
using ScriptStep = std::variant<PressStep, StrokeStep, PathFileStep, HoldStep, MoveStep>;

struct Device {
  // The name a client and VRPN know the device by: `devices[i].name`, by default Phantom<i>
  // (a `device:` section is Phantom0).
  std::string name = "Phantom0";
  DeviceType type = DeviceType::Sim;
  DeviceModel model;                // a copy of the table row (device_models.hpp)
  std::string address;              // VRPN only, e.g. "Phantom0@localhost:3883"
  double stiffness_fraction = 0.5;  // of model.max_stiffness_n_per_m
  double damping_ns_per_m = 0.0;    // virtual damping, at most model.max_damping_ns_per_m
  SimDeviceParams sim;              // Sim only
  std::vector<ScriptStep> script;   // Sim only
  Pen pen;    // its sound (clients/audio)
  Tool tool;  // its touch (hapticd)

  double stiffnessNPerM() const { return stiffness_fraction * model.max_stiffness_n_per_m; }
};

enum class Shape { Sphere, Box, Capsule, Cylinder };

// objects[].texture (issue 29): a relief map on every face of a box, spanning tile_m on each
// (clients/physics/textured_box.hpp lays it out), or a ball's bump map, laid on the six faces of
// a cube projected onto it (meshes/textured_ball_mesh.hpp); a file of normals only is read as the
// relief they integrate to. Built by buildObjectTexture (surface_texture.hpp).
struct ObjectTexture {
  TextureSource source;  // a generator's extent defaults to tile_m
  // texture_tile; default: the generator's extent, else the box's longest edge or the arc of one
  // of the ball's faces (pi r / 2: each face spans one tile)
  double tile_m = 0.02;
};

struct SceneObject {
  std::string name;
  Shape shape = Shape::Sphere;
  double radius_m = 0.0;                             // sphere, capsule, cylinder
  double length_m = 0.0;                             // capsule: between cap centres; cylinder: full height
  Eigen::Vector3d size_m = Eigen::Vector3d::Zero();  // box: full edge lengths
  double mass_kg = 0.0;
  Material material;
  Pose pose;  // centre of mass; capsule and cylinder axes along the object's local z
  Eigen::Vector3d velocity_m_per_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_rad_per_s = Eigen::Vector3d::Zero();  // world frame
  bool fixed = false;  // a static obstacle (walls, bumpers): never moves, mass_kg = 0
  std::optional<ObjectTexture> texture;  // box or sphere
};

struct Rates {
  int servo_hz = 1000;
  int physics_hz = 1000;
  int visual_hz = 60;
  int audio_hz = 44100;
  int audio_feed_hz = 1000;
};

// What the audio client does with the scene (docs/scenes.md, audio).
struct Audio {
  bool mute = false;  // the audio client plays exact silence while this scene runs (Study 1's "no sound")
};

struct Scene {
  int version = 1;
  std::string name;
  std::string description;
  std::string source;    // the file (or in-memory source name) it was read from
  std::string base_dir;  // relative paths in the scene resolved against this
  Surface surface;
  Device device;  // the only device (`device:`), or the first of `devices:`
  // Issue 30: the devices a `devices:` list gives after its first, in order (empty for `device:`).
  std::vector<Device> other_devices;
  std::vector<SceneObject> objects;
  Rates rates;
  Audio audio;
  std::vector<Material> custom_materials;  // the scene's `materials:` (beside the table's)
  std::vector<std::string> warnings;  // non-fatal issues, each "file:line:col: field: message"
};

// One servo clock serves at most this many devices (srv::ServoGroup::kMaxDevices).
inline constexpr std::size_t kMaxSceneDevices = 16;
inline std::size_t deviceCount(const Scene& scene) { return 1 + scene.other_devices.size(); }
// Device i of deviceCount(scene): 0 is scene.device.
inline const Device& deviceAt(const Scene& scene, std::size_t i) {
  return i == 0 ? scene.device : scene.other_devices.at(i - 1);
}
// The scene as device i alone sees it: `device` is device i and there are no others. hapticd runs
// every one-device translation (server/scene_device.hpp: spec, simulated hand, renderer) on it.
inline Scene sceneForDevice(const Scene& scene, std::size_t i) {
  Scene one = scene;
  one.device = deviceAt(scene, i);
  one.other_devices.clear();
  return one;
}

const char* toString(DeviceType type);
const char* toString(Shape shape);
const char* toString(SlabSupport held);

}  // namespace thx::scene
