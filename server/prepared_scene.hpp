#pragma once
// A scene made ready for the servo, off the servo thread: loaded, checked against the running
// device and the command line's policy, its surface built, its renderer configured, its
// stability budget checked. hapticd prepares its first scene here and every scene a client
// switches to (server/scene_switcher.hpp), so a switched-to scene is held to exactly the checks
// of a scene given at start. Configuration time only: allocates, reads files, throws.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "device/haptic_device.hpp"
#include "scenes/scene.hpp"
#include "scenes/scene_surface.hpp"
#include "server/capsule_tool.hpp"
#include "server/mesh_scene.hpp"
#include "server/servo.hpp"
#include "server/servo_rig.hpp"
#include "server/stability_budget.hpp"

namespace thx::srv {

// What hapticd's command line fixes for every scene it runs.
struct ScenePolicy {
  std::optional<double> stiffness_fraction;  // --stiffness-fraction: overrides the scene's
  bool crease = true;                        // --no-crease
  bool passivity = true;                     // --no-passivity
  bool strict_stability = false;             // --strict-stability
  // --paper-loop [--plane-rate HZ]: the source paper's loop (server/paper_loop.hpp) with one
  // plane per this many hertz; overrides crease and passivity.
  std::optional<double> paper_loop_plane_hz;
  // --device vrpn:ADDRESS: the device renders the plane proxies it is sent (OutputMode::Planes), so
  // a scene's capsule tool (device.tool), a force the server computes, is refused.
  bool device_renders_planes = false;
};

// One device's part of a prepared scene: what its servo renders the scene with.
struct PreparedDevice {
  ServoRigConfig wiring;   // servoRigConfigFor() of the device's view of the scene, the policy applied
  StabilityBudget budget;  // ok (a failing budget throws); its message is a note
  // A mesh scene: the renderer this device's servo runs on the mesh (it keeps the device's proxy,
  // so each device has its own); else null.
  std::unique_ptr<TexturedMeshRenderer> mesh_renderer;
  // device.tool: capsule: the pen with extent this device's servo renders (server/capsule_tool.hpp),
  // on the scene's surface; else null (the point pen).
  std::unique_ptr<CapsuleTool> tool;
  SurfaceSwap swap;  // points into the scene's `surface`, `mesh_renderer` and `tool`
};

struct PreparedScene {
  std::string path;                   // the scene file
  scene::SceneSurface surface;        // owned, shared read-only by every device's servo
  std::vector<std::string> warnings;  // the loader's
  // A mesh scene (surface.mesh): the mesh every device's renderer runs on; else null.
  std::shared_ptr<const MeshGeometry> mesh;
  // hello_t.texture_fingerprint: the surface's texture fingerprint, hashed with the mesh for a
  // mesh scene (scene::meshSceneFingerprint).
  std::uint64_t fingerprint = 0;
  // One per scene device (scene::deviceAt order), sized once: a PreparedScene never moves and
  // its devices never reallocate, so their swaps stay valid while the servos hold them.
  std::vector<PreparedDevice> devices;
};

// Builds the scene `scene` (loaded from `path`) for its devices, device i having `specs[i]` (one
// spec per scene device). Throws thx::Error naming the scene file: a spec count that differs from
// the scene's devices, the texture's errors, the mesh's, a smoothing the server cannot do, a
// device's stability budget the policy refuses (naming the device when there are several), the
// paper's loop on a mesh or with a capsule tool, a capsule tool on a device that renders planes. `mesh`: the scene's mesh if the caller has built it already (hapticd
// does, for the simulated hand), else it is built here.
std::unique_ptr<PreparedScene> prepareScene(const scene::Scene& scene, const std::string& path,
                                            const std::vector<dev::DeviceSpec>& specs, const ScenePolicy& policy,
                                            std::shared_ptr<const MeshGeometry> mesh = nullptr);

// A scene to switch to while `running` runs on its devices: loads `path` (scene errors carry
// file:line), refuses what a switch cannot change (the number of devices, each device's model,
// the servo rate: they need a restart), then prepareScene(). Throws thx::Error.
std::unique_ptr<PreparedScene> prepareSwitch(const std::string& path, const scene::Scene& running,
                                             const std::vector<dev::DeviceSpec>& specs, const ScenePolicy& policy);

}  // namespace thx::srv
