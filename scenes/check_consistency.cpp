// Cross-section checks: each is legal on its own but likely a mistake in combination.
#include <cmath>
#include <utility>
#include <vector>

#include "scenes/scene_frames.hpp"
#include "scenes/scene_sections.hpp"

namespace thx::scene::detail {

namespace {

// The deepest field along `keys` that the file has (the root if none), for warnings that
// concern a default as much as a written value.
Field deepest(const Field& root, std::initializer_list<const char*> keys) {
  std::optional<Field> f(root);
  for (const char* key : keys) {
    auto next = f->find(key);
    if (!next) break;
    f.emplace(*next);
  }
  return *f;
}

// Every device with the section it came from (`device:`, an item of `devices:`, or the root when
// the file has neither).
std::vector<std::pair<const Device*, Field>> deviceSections(const Field& root, const Scene& scene) {
  std::vector<std::pair<const Device*, Field>> out;
  if (const auto list = root.find("devices")) {
    const std::vector<Field> items = list->items();
    for (std::size_t i = 0; i < items.size() && i < deviceCount(scene); ++i) out.emplace_back(&deviceAt(scene, i), items[i]);
  } else {
    out.emplace_back(&scene.device, deepest(root, {"device"}));
  }
  return out;
}

void checkRates(const Field& root, const Scene& scene) {
  const Rates& r = scene.rates;
  for (const auto& [device, section] : deviceSections(root, scene))
    if (device->type == DeviceType::Sim && device->sim.integration_hz % r.servo_hz != 0)
      deepest(section, {"sim", "integration_hz"})
          .warn("sim integration rate " + std::to_string(device->sim.integration_hz) +
                " Hz is not a multiple of rates.servo_hz " + std::to_string(r.servo_hz) +
                " Hz: the zero-order-hold force jitters by a sub-step");
  if (r.audio_feed_hz > r.servo_hz)
    deepest(root, {"rates", "audio_feed_hz"})
        .warn("audio_feed_hz " + std::to_string(r.audio_feed_hz) + " Hz is above servo_hz " +
              std::to_string(r.servo_hz) + " Hz: the audio client would receive repeated contact states");
  if (r.physics_hz > r.servo_hz)
    deepest(root, {"rates", "physics_hz"})
        .warn("physics_hz above servo_hz: pen forces reach physics no faster than the servo produces them");
}

// Script points the device cannot reach are not errors (the pose may be changed later) but
// the hand would stop at the workspace edge.
void checkWorkspace(const Field& section, const Device& device, const Scene& scene) {
  const tex::PlaneMapping mapping = planeMapping(scene.surface);
  const double radius = device.model.workspace_radius_m;
  const auto check = [&](const Eigen::Vector2d& p, std::size_t index) {
    const Eigen::Vector3d p_world = mapping.toWorld(Eigen::Vector3d(p.x(), p.y(), 0.0));
    if (p_world.norm() > radius)
      deepest(section, {"script"})
          .warn("script step " + std::to_string(index) + " reaches [" + formatNumber(p.x()) + ", " +
                formatNumber(p.y()) + "], " + formatNumber(p_world.norm()) + " m from the device origin, beyond the " +
                device.model.name + " workspace radius " + formatNumber(radius) + " m");
  };
  for (std::size_t i = 0; i < device.script.size(); ++i) {
    const ScriptStep& step = device.script[i];
    if (const auto* press = std::get_if<PressStep>(&step)) check(press->position_m, i);
    if (const auto* stroke = std::get_if<StrokeStep>(&step)) {
      check(stroke->from_m, i);
      check(stroke->to_m, i);
    }
    if (const auto* move = std::get_if<MoveStep>(&step)) check(move->to_m.head<2>(), i);
  }
}

}  // namespace

void warnAboutInconsistencies(const Field& root, const Scene& scene) {
  checkRates(root, scene);
  for (const auto& [device, section] : deviceSections(root, scene)) checkWorkspace(section, *device, scene);
}

}  // namespace thx::scene::detail
