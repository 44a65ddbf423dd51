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
  if (const std::vector<Material>* custom = field.context().custom_materials) {
    for (const Material& m : *custom)
      if (m.name == name) return m;
    for (const Material& m : *custom) names.push_back(m.name);
  }
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

namespace {
// Poisson's ratio gets its own message: 0.5 is the incompressible limit, where the elastic
// stiffness (Lamé lambda) is infinite and the modal analysis cannot run.
double parsePoisson(const Field& field) {
  NumberRange any;
  const double nu = field.number(any);
  const std::string expected = "a number in (-1, 0.5)";
  if (nu >= 0.5) field.fail("Poisson's ratio of 0.5 or more is incompressible (the elastic stiffness is singular)", expected);
  if (nu <= -1.0) field.fail("Poisson's ratio of -1 or less is not a stable elastic material", expected);
  return nu;
}

Material customMaterial(const Field& field, const std::vector<Material>& earlier) {
  field.expectKeys({"name", "density", "youngs_modulus", "poisson_ratio", "rayleigh_alpha", "rayleigh_beta", "friction",
                    "restitution", "rolling_friction", "spinning_friction"});
  if (field.isNull()) field.fail("missing value", "a mapping with name, density, youngs_modulus, poisson_ratio");
  Material m;
  const Field name = field.at("name", "a material name not in the materials table");
  m.name = name.text();
  if (findMaterial(m.name)) name.fail("already in the materials table", "a new name (or use the table's by name)");
  for (const Material& e : earlier)
    if (e.name == m.name) name.fail("defined twice", "a unique name among the scene's materials");
  m.density_kg_per_m3 = field.at("density", "kg/m^3").number(positiveUpTo(1e5, "kg/m^3"));
  m.youngs_modulus_pa = field.at("youngs_modulus", "Pa").number(positiveUpTo(1e13, "Pa"));
  m.poisson_ratio = parsePoisson(field.at("poisson_ratio", "a number in (-1, 0.5)"));
  if (auto f = field.find("rayleigh_alpha")) m.rayleigh_alpha_per_s = f->number(closedRange(0.0, 1e4, "1/s"));
  if (auto f = field.find("rayleigh_beta")) m.rayleigh_beta_s = f->number(closedRange(0.0, 1e-2, "s"));
  m.friction = 0.5;
  m.restitution = 0.5;
  if (auto f = field.find("friction")) m.friction = f->number(closedRange(0.0, 10.0, ""));
  if (auto f = field.find("restitution")) m.restitution = f->number(closedRange(0.0, 1.0, ""));
  if (auto f = field.find("rolling_friction")) m.rolling_friction_m = f->number(closedRange(0.0, 0.01, "m"));
  if (auto f = field.find("spinning_friction")) m.spinning_friction_m = f->number(closedRange(0.0, 0.01, "m"));
  m.source = "scene " + field.location().file;
  return m;
}
}  // namespace

std::vector<Material> parseCustomMaterials(const std::optional<Field>& field) {
  std::vector<Material> out;
  if (!field || field->isNull()) return out;
  for (const Field& item : field->items()) out.push_back(customMaterial(item, out));
  return out;
}

Pen parsePen(const Field& field) {
  field.expectKeys({"radius", "length", "material", "tilt_deg"});
  Pen pen;
  pen.material = *findMaterial("plastic");
  if (field.isNull()) return pen;
  if (auto f = field.find("radius")) pen.radius_m = f->number(positiveUpTo(0.1, "m"));
  if (auto f = field.find("length")) pen.length_m = f->number(positiveUpTo(1.0, "m"));
  if (pen.length_m < 2 * pen.radius_m)
    field.fail("the pen is shorter than it is wide", "length >= 2 x radius",
               formatNumber(pen.length_m) + " m long, radius " + formatNumber(pen.radius_m) + " m");
  if (auto f = field.find("material")) pen.material = parseMaterial(*f);
  if (auto f = field.find("tilt_deg")) pen.tilt_deg = f->number(closedRange(0.0, 89.0, "deg"));
  return pen;
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

FileOrGenerator parseFileOrGenerator(const Field& field, const std::vector<std::string>& keys, const std::string& what,
                                     const std::string& expected) {
  if (field.isNull()) field.fail("missing value", expected);
  field.expectKeys(keys);
  FileOrGenerator source{field.find("file"), field.find("generator")};
  if (source.file && source.generator) field.fail("both file and generator given", "exactly one of them", "");
  if (!source.file && !source.generator) field.fail("no " + what + " source", expected, "");
  return source;
}

void refuseKeys(const Field& field, std::initializer_list<const char*> keys, const std::string& only_to,
                const std::string& with) {
  for (const char* key : keys)
    if (auto extra = field.find(key))
      extra->fail("applies only to " + only_to, "no '" + std::string(key) + "' with " + with, "");
}

}  // namespace thx::scene::detail
