// device.script: what the simulated hand does, step by step.
#include <cmath>

#include "scenes/scene_sections.hpp"

namespace thx::scene::detail {

namespace {

constexpr double kMaxStepDurationS = 3600.0;
constexpr double kMaxStrokeSpeedMPerS = 2.0;  // faster than any hand stroke

// Positions are surface-local and must lie on the textured rectangle the scene defines. On a mesh
// they are (x, y) in the surface frame: hapticd checks that the mesh lies under each when it builds
// the scene (server/prepared_scene.hpp), as the mesh is not read here.
Eigen::Vector2d parsePoint(const Field& field, const Surface& surface) {
  const Eigen::Vector2d p = field.vector2(closedRange(-100.0, 100.0, "m"));
  if (surface.mesh) return p;
  const Eigen::Vector2d half = surface.size_m / 2.0;
  if (std::fabs(p.x()) > half.x() || std::fabs(p.y()) > half.y())
    field.fail("outside the surface",
               "a surface-local point [x, y] within [" + formatNumber(-half.x()) + ", " + formatNumber(half.x()) +
                   "] x [" + formatNumber(-half.y()) + ", " + formatNumber(half.y()) + "] m",
               "[" + formatNumber(p.x()) + ", " + formatNumber(p.y()) + "]");
  return p;
}

double parseForce(const Field& field, const DeviceModel& model) {
  const double f = field.number(positiveUpTo(model.peak_force_n, "N (peak force of " + model.name + ")"));
  if (f > model.continuous_force_n)
    field.warn("force " + formatNumber(f) + " N is above the continuous force of " + model.name + " (" +
               formatNumber(model.continuous_force_n) + " N): the safety stage will limit a long push");
  return f;
}

PressStep parsePress(const Field& field, const Surface& surface, const DeviceModel& model) {
  field.expectKeys({"position", "force", "duration"});
  if (field.isNull()) field.fail("missing value", "{position: [x, y], force: N, duration: s}");
  PressStep step;
  step.position_m = parsePoint(field.at("position", "[x, y] surface-local, in metres"), surface);
  step.force_n = parseForce(field.at("force", "the normal force in newtons"), model);
  step.duration_s = field.at("duration", "seconds").number(positiveUpTo(kMaxStepDurationS, "s"));
  return step;
}

StrokeStep parseStroke(const Field& field, const Surface& surface, const DeviceModel& model) {
  field.expectKeys({"from", "to", "speed", "force"});
  if (field.isNull()) field.fail("missing value", "{from: [x, y], to: [x, y], speed: m/s, force: N}");
  StrokeStep step;
  step.from_m = parsePoint(field.at("from", "[x, y] surface-local, in metres"), surface);
  const Field to = field.at("to", "[x, y] surface-local, in metres");
  step.to_m = parsePoint(to, surface);
  if (step.to_m == step.from_m) to.fail("zero-length stroke", "an end point different from 'from'");
  step.speed_m_per_s = field.at("speed", "metres per second").number(positiveUpTo(kMaxStrokeSpeedMPerS, "m/s"));
  step.force_n = parseForce(field.at("force", "the normal force in newtons"), model);
  return step;
}

HoldStep parseHold(const Field& field) {
  field.expectKeys({"duration"});
  if (field.isNull()) field.fail("missing value", "{duration: s}");
  return {field.at("duration", "seconds").number(positiveUpTo(kMaxStepDurationS, "s"))};
}

MoveStep parseMove(const Field& field, const Surface& surface, const DeviceModel& model) {
  field.expectKeys({"to", "push", "duration"});
  if (field.isNull()) field.fail("missing value", "{to: [x, y, z], push: [fx, fy, fz], duration: s}");
  // The move's heights are the plane's; on a mesh the hand's heights follow the mesh instead.
  if (surface.mesh)
    field.fail("a move needs a plane surface", "press, stroke, path_file or hold steps on a mesh (surface.mesh)");
  MoveStep step;
  const Field to = field.at("to", "[x, y, z]: a surface-local point and its height above the surface, in metres");
  const Eigen::Vector3d p = to.vector3(closedRange(-100.0, 100.0, "m"));
  const Eigen::Vector2d half = surface.size_m / 2.0;
  if (std::fabs(p.x()) > half.x() || std::fabs(p.y()) > half.y() || p.z() < -0.05 || p.z() > 0.3)
    to.fail("outside the hand's room",
            "[x, y, z] with x, y within [" + formatNumber(-half.x()) + ", " + formatNumber(half.x()) + "] x [" +
                formatNumber(-half.y()) + ", " + formatNumber(half.y()) + "] m and z in [-0.05, 0.3] m",
            "[" + formatNumber(p.x()) + ", " + formatNumber(p.y()) + ", " + formatNumber(p.z()) + "]");
  step.to_m = p;
  if (auto f = field.find("push")) {
    step.push_n = f->vector3(closedRange(-model.peak_force_n, model.peak_force_n, "N"));
    if (step.push_n.norm() > model.peak_force_n)
      f->fail("push above the peak force of " + model.name,
              "a push of at most " + formatNumber(model.peak_force_n) + " N", formatNumber(step.push_n.norm()) + " N");
  }
  step.duration_s = field.at("duration", "seconds").number(positiveUpTo(kMaxStepDurationS, "s"));
  return step;
}

ScriptStep parseStep(const Field& step, const Surface& surface, const DeviceModel& model) {
  const std::string expected = "exactly one of press, stroke, path_file, hold, move";
  step.expectKeys({"press", "stroke", "path_file", "hold", "move"});
  const auto actions = step.entries();
  if (actions.size() != 1) step.fail(actions.empty() ? "empty step" : "more than one action in a step", expected);
  const auto& [action, body] = actions.front();
  if (action == "press") return parsePress(body, surface, model);
  if (action == "stroke") return parseStroke(body, surface, model);
  if (action == "hold") return parseHold(body);
  if (action == "move") return parseMove(body, surface, model);
  return PathFileStep{parseExistingFile(body, "path file (CSV rows t_s, x_m, y_m, force_n)")};
}

}  // namespace

std::vector<ScriptStep> parseScript(const Field& field, const Surface& surface, const DeviceModel& model) {
  std::vector<ScriptStep> script;
  for (const Field& step : field.items()) script.push_back(parseStep(step, surface, model));
  return script;
}

}  // namespace thx::scene::detail
