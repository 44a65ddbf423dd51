#pragma once
// Haptic device models: the limits the server's stability budget and safety stage start from.
// Peak force, stiffness, damping and workspace are CHAI3D 3.3.0's table (docs/scenes.md "Device
// models"). That table gives no continuous force, so it is an assumption:
// kContinuousForceFraction of the peak (same section).
#include <string>
#include <string_view>
#include <vector>

namespace thx::scene {

inline constexpr double kContinuousForceFraction = 0.15;

struct DeviceModel {
  std::string name;
  double peak_force_n = 0.0;
  double continuous_force_n = 0.0;  // kContinuousForceFraction * peak_force_n
  double max_stiffness_n_per_m = 0.0;
  double max_damping_ns_per_m = 0.0;
  double workspace_radius_m = 0.0;
};

const std::vector<DeviceModel>& deviceModels();
const DeviceModel* findDeviceModel(std::string_view name);  // nullptr if unknown

}  // namespace thx::scene
