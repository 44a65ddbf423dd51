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
};

struct PreparedScene {
  std::string path;                   // the scene file
  scene::SceneSurface surface;        // owned: the servo renders surface.surface (or its map on the mesh)
  ServoRigConfig wiring;              // servoRigConfigFor() with the policy applied
  StabilityBudget budget;             // ok (a failing budget throws); its message is a note
  std::vector<std::string> warnings;  // the loader's
  // A mesh scene (surface.mesh): the mesh and the renderer the servo runs on it; else both null.
  std::shared_ptr<const MeshGeometry> mesh;
  std::unique_ptr<TexturedMeshRenderer> mesh_renderer;
  // hello_t.texture_fingerprint: the surface's texture fingerprint, hashed with the mesh for a
  // mesh scene (scene::meshSceneFingerprint).
  std::uint64_t fingerprint = 0;
  SurfaceSwap swap;                   // points into `surface` and `mesh_renderer`: a PreparedScene never moves
};

// Builds the scene `scene` (loaded from `path`) for a device with `spec`. Throws thx::Error
// naming the scene file: the texture's errors, the mesh's, a smoothing the server cannot do, a
// stability budget the policy refuses, the paper's loop on a mesh. `mesh`: the scene's mesh if the
// caller has built it already (hapticd does, for the simulated hand), else it is built here.
std::unique_ptr<PreparedScene> prepareScene(const scene::Scene& scene, const std::string& path,
                                            const dev::DeviceSpec& spec, const ScenePolicy& policy,
                                            std::shared_ptr<const MeshGeometry> mesh = nullptr);

// A scene to switch to while `running` runs on its device: loads `path` (scene errors carry
// file:line), refuses what a switch cannot change (the device model, the servo rate: they need a
// restart), then prepareScene(). Throws thx::Error.
std::unique_ptr<PreparedScene> prepareSwitch(const std::string& path, const scene::Scene& running,
                                             const dev::DeviceSpec& spec, const ScenePolicy& policy);

}  // namespace thx::srv
