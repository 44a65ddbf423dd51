#include "scenes/device_models.hpp"

namespace thx::scene {

namespace {
DeviceModel model(const char* name, double peak_n, double stiffness, double damping, double radius_m) {
  return {name, peak_n, kContinuousForceFraction * peak_n, stiffness, damping, radius_m};
}
}  // namespace

const std::vector<DeviceModel>& deviceModels() {
  // clang-format off
  static const std::vector<DeviceModel> table = {
      //    name               peak N  K N/m   b N·s/m  workspace m
      model("phantom_desktop", 7.9,    1000.0, 5.0,     0.10),
      model("phantom_omni",    3.3,    700.0,  5.0,     0.10),
      model("touch",           3.3,    400.0,  4.0,     0.075),
      model("premium_1_5",     8.5,    800.0,  5.0,     0.12),
      model("premium_3_0",     22.0,   1000.0, 5.0,     0.12),
      model("generic",         6.0,    1000.0, 8.0,     0.10),
  };
  // clang-format on
  return table;
}

const DeviceModel* findDeviceModel(std::string_view name) {
  for (const DeviceModel& m : deviceModels())
    if (m.name == name) return &m;
  return nullptr;
}

}  // namespace thx::scene
