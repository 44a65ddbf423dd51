#pragma once
// From a scene to the server's parts: the device spec, the simulated PHANToM and its hand
// script, hapticd's device, the renderer's configuration. Scenes know nothing of devices and devices nothing of
// scenes; this is the one place that translates.
#include <memory>
#include <string>

#include "device/hand_script.hpp"
#include "device/haptic_device.hpp"
#include "device/sim_config.hpp"
#include "device/surface_height.hpp"
#include "scenes/scene.hpp"
#include "server/capsule_tool.hpp"
#include "server/proxy_renderer.hpp"
#include "server/servo_rig.hpp"

namespace thx::dev {
class SimPhantom;
class ReplayDevice;
}  // namespace thx::dev

namespace thx::srv {

// The scene's model row, plus what the scene table does not carry: position resolution from the
// sim parameters, physical damping from the simulator's PHANToM assumption (device_specs.cpp).
dev::DeviceSpec deviceSpecFor(const scene::Scene& scene);

dev::SimPhantomConfig simConfigFor(const scene::Scene& scene, bool lockstep);

// Reads path files (device/hand_script.hpp); throws dev::HandScriptError naming file and line.
// On a mesh (`hand_surface`, a mesh scene's heights) the hand comes down from above the mesh's
// top onto each contact step: the descent and ascent take long enough that the hand moves at
// kHandApproachSpeed on average, as it does over the plane's hover height (5 mm in 0.2 s) at the
// least, so a deep bowl is not struck at speed.
inline constexpr double kHandApproachSpeedMPerS = 0.05;
dev::HandScript handScriptFor(const scene::Scene& scene, const dev::SurfaceHeight* hand_surface = nullptr);

// hapticd's device: the replay of a recorded session (`device_option` "replay:FILE", paced at the
// scene's servo rate), a VRPN client of `vrpn_address` when that is set, else the scene's simulated
// PHANToM and hand script. `sim` and `replay` point into `device` when it is one of them. Throws
// thx::Error naming the file or address.
struct SceneDevice {
  std::unique_ptr<dev::HapticDevice> device;
  dev::SimPhantom* sim = nullptr;
  dev::ReplayDevice* replay = nullptr;
};
// `hand_surface`: a mesh scene's heights for the simulated hand (SimPhantomConfig::surface_height;
// it must outlive the device), nullptr on the plane.
// `spin_ns`: the simulated or VRPN device's pacer busy-waits the last spin_ns of each period
// (rt::Pacer; hapticd --spin-us), in real time only.
// `replay_device`: which device of the recorded session a replay plays (its index in the log).
SceneDevice makeSceneDevice(const scene::Scene& scene, const std::string& device_option,
                            const std::string& vrpn_address, bool lockstep,
                            const dev::SurfaceHeight* hand_surface = nullptr, std::int64_t spin_ns = 0,
                            int replay_device = 0);

// A mesh scene's script against its mesh: every point a press, stroke or path step touches must
// have the mesh under it (seen from above in the surface frame), or the hand would press on
// nothing. Throws thx::Error (Config) naming the scene file, the step and the point.
void checkScriptOnMesh(const scene::Scene& scene, const dev::SurfaceHeight& hand_surface);

RendererConfig rendererConfigFor(const scene::Scene& scene);

// hapticd's servo wiring for the scene (server/servo_rig.hpp): its renderer, its servo period,
// the passivity controller on with the quantisation play, one second of flight record, a
// 1024-record (1 s) tick ring.
ServoRigConfig servoRigConfigFor(const scene::Scene& scene);

// A capsule tool (device.tool: capsule) for a servo at period_s: the scene's shape and turning
// stiffness, the renderer's stiffness and virtual damping as the coupling's (a device caps them
// again), its ramp 0.5 s.
CapsuleToolConfig capsuleToolConfigFor(const scene::Tool& tool, const RendererConfig& renderer, double period_s);

}  // namespace thx::srv
