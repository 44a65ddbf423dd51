// Small readers several sections share: poses, materials, files that must exist.
#include <filesystem>

#include "scenes/scene_sections.hpp"

namespace thx::scene::detail {

Pose parsePose(const Field& field) {
  field.expectKeys({"position", "rpy_deg"});
  Pose pose;
  if (auto p = field.find("position")) pose.position_m = p->vector3(closedRange(-100.0, 100.0, "m"));
  if (auto r = field.find("rpy_deg"))
    pose.rpy_deg = r->vector3(closedRange(-360.0, 360.0, "deg"), "[roll, pitch, yaw]");
  return pose;
}

namespace {
Material namedMaterial(const Field& field) {
  std::vector<std::string> names;
  for (const Material& m : materials()) names.push_back(m.name);
  const std::string name = field.text();
  if (const Material* m = findMaterial(name)) return *m;
  const std::string guess = closestMatch(name, names);
  field.fail(guess.empty() ? "unknown material" : "unknown material (did you mean '" + guess + "'?)",
             "one of: " + joinNames(names));
}
}  // namespace

Material parseMaterial(const Field& field) {
  if (!field.isMapping()) return namedMaterial(field);
  // The table's material with the scene's own rolling and spinning friction.
  field.expectKeys({"name", "rolling_friction", "spinning_friction"});
  Material m = namedMaterial(field.at("name", "a material name (materials table)"));
  if (auto r = field.find("rolling_friction")) m.rolling_friction_m = r->number(closedRange(0.0, 0.01, "m"));
  if (auto s = field.find("spinning_friction")) m.spinning_friction_m = s->number(closedRange(0.0, 0.01, "m"));
  return m;
}

std::string parseExistingFile(const Field& field, const std::string& what) {
  const std::string written = field.text();
  const std::string resolved = field.resolvePath(written);
  const std::string base =
      field.context().base_dir.empty() ? std::string("the current directory") : "'" + field.context().base_dir + "'";
  const std::string expected = "an existing " + what + "; relative paths resolve against " + base;
  std::error_code ec;
  const auto status = std::filesystem::status(resolved, ec);
  if (!std::filesystem::exists(status)) field.fail("file not found: '" + resolved + "'", expected);
  if (!std::filesystem::is_regular_file(status)) field.fail("not a regular file: '" + resolved + "'", expected);
  return resolved;
}

}  // namespace thx::scene::detail
