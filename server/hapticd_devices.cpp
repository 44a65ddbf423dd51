#include "server/hapticd_devices.hpp"

#include <algorithm>

#include "base/error.hpp"
#include "device/replay_device.hpp"
#include "device/sim_phantom.hpp"

namespace thx::srv {

namespace {

std::string joined(const std::vector<std::string>& items) {
  std::string all;
  for (const std::string& s : items) all += (all.empty() ? "" : ",") + s;
  return all;
}

Error configError(const scene::Scene& sc, const std::string& what) {
  return Error(Error::Kind::Config, sc.source + ": " + what);
}

bool isVrpn(const scene::Device& d) { return d.type == scene::DeviceType::Vrpn; }

}  // namespace

std::string HapticdDevices::joinedNames() const { return joined(names); }
std::string HapticdDevices::joinedSources() const { return joined(sources); }

double HapticdDevices::defaultDurationS() const {
  double longest = 0.0;
  for (const SceneDevice& d : devices) {
    if (d.sim) longest = std::max(longest, d.sim->script().duration() + 0.5);
    if (d.replay) longest = std::max(longest, d.replay->durationS());
  }
  return longest;
}

dev::DeviceSpec mostCautiousSpec(const std::vector<dev::DeviceSpec>& specs) {
  dev::DeviceSpec spec = specs.at(0);
  for (const dev::DeviceSpec& s : specs) {
    spec.workspace_radius_m = std::min(spec.workspace_radius_m, s.workspace_radius_m);
    spec.peak_force_n = std::min(spec.peak_force_n, s.peak_force_n);
    spec.continuous_force_n = std::min(spec.continuous_force_n, s.continuous_force_n);
    spec.max_stiffness_n_per_m = std::min(spec.max_stiffness_n_per_m, s.max_stiffness_n_per_m);
    spec.max_damping_ns_per_m = std::min(spec.max_damping_ns_per_m, s.max_damping_ns_per_m);
  }
  return spec;
}

bool HapticdDevices::allSimulated() const {
  return std::all_of(devices.begin(), devices.end(), [](const SceneDevice& d) { return d.sim || d.replay; });
}

void checkOptionsForDevices(const HapticdOptions& o, const scene::Scene& sc) {
  const std::size_t count = scene::deviceCount(sc);
  if (count > 1) {
    const std::string many = "the scene lists " + std::to_string(count) + " devices: ";
    // A recorded session of several devices replays them all, device i from the log's device i.
    if (!o.device.empty() && o.device.rfind("replay:", 0) != 0)
      throw configError(sc, many + "--device replaces a scene's one device; give each device's sim or vrpn in the scene "
                                   "(--device replay:FILE replays a session of as many devices)");
    if (o.vrpn_name_given)
      throw configError(sc, many + "--vrpn-name names one device; with several each is served under its scene name");
  }
  if (!o.lockstep) return;
  for (std::size_t i = 0; i < count; ++i) {
    const bool vrpn = o.device.empty() ? isVrpn(scene::deviceAt(sc, i)) : o.device.rfind("vrpn:", 0) == 0;
    if (vrpn)
      throw configError(sc, "--lockstep needs simulated or replayed devices; device " + scene::deviceAt(sc, i).name +
                                " is VRPN");
  }
}

HapticdDevices makeHapticdDevices(const HapticdOptions& o, const scene::Scene& sc,
                                  const dev::SurfaceHeight* hand_surface) {
  checkOptionsForDevices(o, sc);
  const std::size_t count = scene::deviceCount(sc);
  HapticdDevices out;
  for (std::size_t i = 0; i < count; ++i) {
    const scene::Scene one = count == 1 ? sc : scene::sceneForDevice(sc, i);
    const std::string vrpn_address = vrpnAddress(o, isVrpn(one.device) ? one.device.address : std::string());
    const bool replay = o.device.rfind("replay:", 0) == 0;
    if (hand_surface && !replay && vrpn_address.empty()) checkScriptOnMesh(one, *hand_surface);
    try {
      out.devices.push_back(makeSceneDevice(one, o.device, vrpn_address, o.lockstep, hand_surface, o.spin_ns, int(i)));
    } catch (const thx::Error& e) {
      if (count == 1 || !replay) throw;
      throw thx::Error(e.kind(), "device " + one.device.name + " (" + std::to_string(i) + " of the scene's " +
                                     std::to_string(count) + "): " + e.what());
    }
    out.specs.push_back(out.devices.back().device->spec());
    out.names.push_back(one.device.name);
    out.sources.push_back(vrpn_address.empty() ? "sim" : vrpn_address);  // a replay too, as before
    out.vrpn_addresses.push_back(vrpn_address);
  }
  return out;
}

}  // namespace thx::srv
