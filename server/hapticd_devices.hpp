#pragma once
// hapticd's devices for a scene: one per scene device (issue 30), in the scene's order, each built
// from the scene as that device alone sees it (scene::sceneForDevice) by makeSceneDevice. Also
// what hapticd's command line cannot do with several devices, refused before anything opens.
// Configuration time only: allocates, reads files, throws.
#include <memory>
#include <string>
#include <vector>

#include "device/surface_height.hpp"
#include "scenes/scene.hpp"
#include "server/hapticd_options.hpp"
#include "server/scene_device.hpp"

namespace thx::srv {

struct HapticdDevices {
  std::vector<SceneDevice> devices;    // device i of the scene
  std::vector<dev::DeviceSpec> specs;  // each device's spec
  std::vector<std::string> names;      // each device's scene name (Phantom0, or its `devices:` name)
  std::vector<std::string> sources;    // each device's VRPN address, or "sim" (simulated or replayed)
  std::vector<std::string> vrpn_addresses;  // each device's VRPN address; "" for the others

  std::size_t size() const { return devices.size(); }
  // "a,b,c": hello_t's device_names and device fields.
  std::string joinedNames() const;
  std::string joinedSources() const;
  // The longest simulated script (+0.5 s) or replay: how long a run lasts by default; 0 when
  // every device is real (hapticd then runs until told to stop).
  double defaultDurationS() const;
  bool allSimulated() const;  // simulated or replayed: device_state_t's simulated flag
};

// What a VRPN app is told of the devices it may command (workspace, peak force, stiffness): the
// smallest of each over `specs`, so no served name promises more than its device can give.
dev::DeviceSpec mostCautiousSpec(const std::vector<dev::DeviceSpec>& specs);

// Refuses what the options cannot do with this scene's devices: with several devices, --device
// (it replaces the one device), --vrpn-name (each served name is the device's scene name); --lockstep with any VRPN device. Throws thx::Error
// (Config) naming the scene and the option.
void checkOptionsForDevices(const HapticdOptions& o, const scene::Scene& scene);

// Builds every device, closed. A mesh scene's `hand_surface` (its heights, outliving the devices)
// guides the simulated hands, whose scripts are checked against it. Throws thx::Error naming the
// file, address or device.
HapticdDevices makeHapticdDevices(const HapticdOptions& o, const scene::Scene& scene,
                                  const dev::SurfaceHeight* hand_surface);

}  // namespace thx::srv
