// device: type, model, address, stiffness_fraction, damping, sim, script, pen, tool; devices: a list of them, each
// with a name (issue 30).
#include "scenes/scene_sections.hpp"
#include "scenes/vrpn_address.hpp"

namespace thx::scene::detail {

namespace {

DeviceModel parseModel(const Field& field) {
  std::vector<std::string> names;
  for (const DeviceModel& m : deviceModels()) names.push_back(m.name);
  const std::string name = field.text();
  if (const DeviceModel* m = findDeviceModel(name)) return *m;
  const std::string guess = closestMatch(name, names);
  field.fail(guess.empty() ? "unknown device model" : "unknown device model (did you mean '" + guess + "'?)",
             "one of: " + joinNames(names));
}

std::string parseAddress(const Field& field) {
  const std::string text = field.text();
  std::string problem;
  if (!parseVrpnAddress(text, &problem))
    field.fail("malformed VRPN address: " + problem,
               "DEVICE@HOST[:PORT] or DEVICE@tcp://HOST:PORT, e.g. 'Phantom0@localhost:3883'");
  return text;
}

SimDeviceParams parseSim(const Field& field) {
  field.expectKeys({"integration_hz", "encoder_resolution", "device_mass", "friction", "hand_mass", "hand_stiffness",
                    "hand_damping"});
  SimDeviceParams sim;
  if (auto f = field.find("integration_hz")) {
    // docs/design.md §5: far above the servo rate, or the simulator cannot show instability.
    sim.integration_hz = static_cast<int>(f->integer(10000, 1000000, "Hz"));
  }
  if (auto f = field.find("encoder_resolution")) sim.encoder_resolution_m = f->number(positiveUpTo(1e-3, "m"));
  if (auto f = field.find("device_mass")) sim.device_mass_kg = f->number(positiveUpTo(10.0, "kg"));
  if (auto f = field.find("friction")) sim.friction_n = f->number(closedRange(0.0, 10.0, "N"));
  if (auto f = field.find("hand_mass")) sim.hand_mass_kg = f->number(positiveUpTo(10.0, "kg"));
  if (auto f = field.find("hand_stiffness")) sim.hand_stiffness_n_per_m = f->number(closedRange(0.0, 1e5, "N/m"));
  if (auto f = field.find("hand_damping")) sim.hand_damping_ns_per_m = f->number(closedRange(0.0, 1e3, "N·s/m"));
  return sim;
}

Tool parseTool(const Field& field) {
  field.expectKeys({"shape", "length", "radius", "rot_stiffness"});
  Tool tool;
  if (auto f = field.find("shape")) tool.shape = f->choice<ToolShape>({{"point", ToolShape::Point}, {"capsule", ToolShape::Capsule}});
  for (const char* key : {"length", "radius", "rot_stiffness"}) {
    const auto f = field.find(key);
    if (f && tool.shape == ToolShape::Point)
      throw SceneError(f->keyLocation(), f->path(), "applies only to shape: capsule",
                       "no '" + std::string(key) + "' for the point pen, or shape: capsule");
  }
  if (auto f = field.find("length")) tool.length_m = f->number(positiveUpTo(0.3, "m"));
  if (auto f = field.find("radius")) tool.radius_m = f->number(positiveUpTo(0.01, "m"));
  if (auto f = field.find("rot_stiffness")) tool.rot_stiffness_nm_per_rad = f->number(closedRange(0.0, 10.0, "N·m/rad"));
  if (tool.length_m < 2 * tool.radius_m)
    field.fail("the capsule is shorter than it is wide", "length >= 2 x radius",
               formatNumber(tool.length_m) + " m long, radius " + formatNumber(tool.radius_m) + " m");
  return tool;
}

void rejectForVrpn(const std::optional<Field>& field) {
  if (field)
    throw SceneError(field->keyLocation(), field->path(), "applies only to type: sim",
                     "no '" + field->path() + "' with type: vrpn (a real device is moved by a real hand)");
}

// A device's name as VRPN carries it (a sender name) and a client reads it: letters, digits,
// '_', '-', '.', at most 64 characters.
std::string parseDeviceName(const Field& field) {
  const std::string name = field.text();
  bool ok = name.size() <= 64;
  for (const char c : name)
    ok = ok && ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.');
  if (!ok) field.fail("not a device name", "at most 64 letters, digits, '_', '-' or '.', e.g. 'Phantom1' or 'left_hand'");
  return name;
}

Device parseOneDevice(const std::optional<Field>& field, const Surface& surface, bool named) {
  Device d;
  d.model = *findDeviceModel("phantom_desktop");
  d.pen.material = *findMaterial("plastic");
  if (!field) return d;
  std::vector<std::string> keys = {"type", "model", "address", "stiffness_fraction", "damping", "sim", "script", "pen", "tool"};
  if (named) keys.insert(keys.begin(), "name");  // only a `devices:` entry is named
  field->expectKeys(keys);
  if (const auto n = named ? field->find("name") : std::nullopt) d.name = parseDeviceName(*n);
  if (auto p = field->find("pen")) d.pen = parsePen(*p);
  const auto tool = field->find("tool");
  if (tool) d.tool = parseTool(*tool);
  if (tool && d.tool.shape == ToolShape::Capsule && surface.representation == tex::Representation::Normal)
    tool->find("shape")->fail("needs a relief (surface.representation: relief)",
                              "shape: point on a normal map (a shaft rests on a relief's depth)");
  if (tool && d.tool.shape == ToolShape::Capsule && surface.mesh)
    tool->find("shape")->fail("applies only to a textured plane",
                              "shape: point on a mesh surface (surface.mesh: the capsule's contacts are the plane's texels)");
  if (auto t = field->find("type"))
    d.type = t->choice<DeviceType>({{"sim", DeviceType::Sim}, {"vrpn", DeviceType::Vrpn}});
  if (auto m = field->find("model")) d.model = parseModel(*m);

  const auto address = field->find("address");
  if (d.type == DeviceType::Vrpn) {
    if (!address)
      field->absent("address").fail("missing required field for type: vrpn",
                                    "a VRPN device address such as 'Phantom0@localhost:3883'", "");
    d.address = parseAddress(*address);
    rejectForVrpn(field->find("sim"));
    rejectForVrpn(field->find("script"));
    // A VRPN PHANToM renders the plane proxies it is sent (OutputMode::Planes); the capsule's
    // coupling is a force (and torque) the server computes.
    if (tool && d.tool.shape == ToolShape::Capsule)
      tool->find("shape")->fail("applies only to type: sim",
                                "shape: point with type: vrpn (a VRPN PHANToM renders the plane proxies it is sent)");
  } else if (address) {
    address->fail("applies only to type: vrpn", "no address with type: sim (the simulated device is in-process)", "");
  }

  if (auto f = field->find("stiffness_fraction")) {
    d.stiffness_fraction = f->number(closedRange(0.0, 1.0, "(fraction of the model's maximum stiffness)"));
    if (d.stiffness_fraction == 0.0) f->warn("stiffness_fraction 0: the surface renders no force");
  }
  if (auto f = field->find("damping"))
    d.damping_ns_per_m =
        f->number(closedRange(0.0, d.model.max_damping_ns_per_m, "N·s/m (the maximum of model " + d.model.name + ")"));
  if (d.type == DeviceType::Sim) {
    if (auto s = field->find("sim")) d.sim = parseSim(*s);
    if (auto s = field->find("script")) d.script = parseScript(*s, surface, d.model);
  }
  return d;
}

}  // namespace

Device parseDevice(const std::optional<Field>& field, const Surface& surface) {
  return parseOneDevice(field, surface, false);
}

std::vector<Device> parseDevices(const Field& field, const Surface& surface) {
  const std::vector<Field> items = field.items();
  if (items.empty()) field.fail("no devices", "a list of one device or more (or a single `device:` section)");
  if (items.size() > kMaxSceneDevices)
    field.fail("too many devices", "at most " + std::to_string(kMaxSceneDevices) + " (one servo clock's limit)",
               std::to_string(items.size()) + " devices");
  std::vector<Device> devices;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::string default_name = "Phantom" + std::to_string(i);
    Device d = parseOneDevice(items[i], surface, true);
    if (!items[i].has("name")) d.name = default_name;
    for (std::size_t j = 0; j < devices.size(); ++j) {
      const auto where = [&](std::size_t k) {
        const std::optional<Field> n = items[k].find("name");
        return "devices[" + std::to_string(k) + "], line " + std::to_string((n ? *n : items[k]).location().line);
      };
      if (devices[j].name == d.name)
        (items[i].has("name") ? *items[i].find("name") : items[i])
            .fail("duplicate device name '" + d.name + "' (also " + where(j) + ")", "a name no other device uses");
      if (d.type == DeviceType::Vrpn && devices[j].type == DeviceType::Vrpn && devices[j].address == d.address)
        items[i].find("address")->fail("VRPN address given twice (also devices[" + std::to_string(j) + "])",
                                        "one device per address: each PHANToM has its own name or server");
    }
    devices.push_back(std::move(d));
  }
  return devices;
}

}  // namespace thx::scene::detail
