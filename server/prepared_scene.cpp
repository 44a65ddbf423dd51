#include "server/prepared_scene.hpp"

#include "base/number_text.hpp"
#include "scenes/scene_loader.hpp"
#include "server/paper_loop.hpp"
#include "server/passivity.hpp"
#include "server/scene_device.hpp"

namespace thx::srv {

namespace {

thx::Error configError(const std::string& path, const std::string& what) {
  return thx::Error(thx::Error::Kind::Config, path + ": " + what);
}

}  // namespace

namespace {

// Device `i`'s wiring, budget and (on a mesh) renderer. `who`: "" for a scene's only device, else
// the device's name for the errors.
PreparedDevice prepareDevice(const scene::Scene& one, const dev::DeviceSpec& spec, const ScenePolicy& policy,
                             const PreparedScene& p, const std::string& who) {
  PreparedDevice d;
  d.wiring = servoRigConfigFor(one);
  RendererConfig& rc = d.wiring.renderer;
  if (policy.stiffness_fraction) rc.stiffness_n_per_m = *policy.stiffness_fraction * spec.max_stiffness_n_per_m;
  rc.crease_handling = policy.crease;
  d.wiring.passivity = policy.passivity;
  if (policy.paper_loop_plane_hz) applyPaperLoop(d.wiring, *policy.paper_loop_plane_hz);

  const scene::Device& device = scene::deviceAt(one, 0);
  const bool capsule = device.tool.shape == scene::ToolShape::Capsule;
  const std::string field = who.empty() ? "device.tool" : "device " + who + ": tool";
  if (capsule && policy.paper_loop_plane_hz)
    throw configError(p.path, field + ": capsule: --paper-loop renders the point pen; run without it, or shape: point");
  if (capsule && policy.device_renders_planes)
    throw configError(p.path, field + ": capsule: the device renders the plane proxies it is sent (--device vrpn:), "
                                      "and the capsule's coupling is a force the server computes; shape: point");
  if (capsule && !p.surface.surface.usesRelief())
    throw configError(p.path, field + ": capsule needs a relief; the surface's texture holds normals only (no "
                                      "alpha depth): a relief map (RGBA), or shape: point");
  if (capsule) {
    d.tool = std::make_unique<CapsuleTool>(p.surface.surface, spec,
                                           capsuleToolConfigFor(device.tool, rc, d.wiring.period_s));
  }

  StabilityRequest sr;
  sr.stiffness_fraction = (d.tool ? d.tool->stiffness() : rc.stiffness_n_per_m) / spec.max_stiffness_n_per_m;
  // The coupling's damping is the virtual damping the device renders with a capsule.
  sr.virtual_damping_ns_per_m = d.tool ? d.tool->damping() : rc.damping_ns_per_m;
  sr.period_s = d.wiring.period_s;
  sr.policy = policy.strict_stability ? BoundPolicy::Strict : BoundPolicy::Warn;
  d.budget = checkStabilityBudget(spec, sr);
  if (!d.budget.ok) {
    std::string all;
    for (const std::string& e : d.budget.errors) all += (all.empty() ? "" : "; ") + e;
    throw configError(p.path, who.empty() ? all : "device " + who + ": " + all);
  }
  // The servo's passivity observer takes the renderer's stiffness (the coupling's, with a capsule)
  // as its K: checked here, off the servo thread, as the controller's constructor would.
  const double stored_energy_k = d.tool ? d.tool->stiffness() : rc.stiffness_n_per_m;
  servoPassivityConfig(spec, d.wiring.period_s, stored_energy_k, policy.passivity).validate();
  if (p.mesh) d.mesh_renderer = buildMeshRenderer(*p.mesh, p.surface.surface, rc);

  d.swap.surface = &p.surface.surface;
  d.swap.renderer = rc;
  d.swap.stored_energy_stiffness_n_per_m = stored_energy_k;
  d.swap.mesh = d.mesh_renderer.get();
  d.swap.tool = d.tool.get();
  return d;
}

}  // namespace

std::unique_ptr<PreparedScene> prepareScene(const scene::Scene& sc, const std::string& path,
                                            const std::vector<dev::DeviceSpec>& specs, const ScenePolicy& policy,
                                            std::shared_ptr<const MeshGeometry> mesh) {
  const std::size_t count = scene::deviceCount(sc);
  if (specs.size() != count) {
    throw configError(path, "devices: the scene lists " + std::to_string(count) + " device" + (count == 1 ? "" : "s") +
                                " and the server runs " + std::to_string(specs.size()));
  }
  if (sc.surface.mesh && policy.paper_loop_plane_hz)
    throw configError(path, "--paper-loop renders a plane per graphics frame; this scene's surface is a mesh "
                            "(surface.mesh): run it without --paper-loop");
  auto p = std::make_unique<PreparedScene>();
  p->path = path;
  p->warnings = sc.warnings;
  p->surface = scene::buildSceneSurface(sc);
  if (sc.surface.mesh) {
    try {
      p->mesh = mesh ? std::move(mesh) : buildMeshGeometry(sc);
    } catch (const scene::SceneError&) {
      throw;  // names the scene file, line and field already
    } catch (const thx::Error& e) {
      throw configError(path, std::string("surface.mesh: ") + e.what());
    }
  }
  p->fingerprint =
      p->mesh ? scene::meshSceneFingerprint(p->surface.fingerprint, p->mesh->scene_mesh) : p->surface.fingerprint;
  p->devices.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::string who = count == 1 ? std::string() : scene::deviceAt(sc, i).name;
    p->devices.push_back(prepareDevice(count == 1 ? sc : scene::sceneForDevice(sc, i), specs[i], policy, *p, who));
  }
  return p;
}

std::unique_ptr<PreparedScene> prepareSwitch(const std::string& path, const scene::Scene& running,
                                             const std::vector<dev::DeviceSpec>& specs, const ScenePolicy& policy) {
  const scene::Scene sc = scene::loadScene(path);
  const std::size_t count = scene::deviceCount(running);
  if (scene::deviceCount(sc) != count) {
    throw configError(path, "the scene lists " + std::to_string(scene::deviceCount(sc)) + " device(s), the running "
                                "server " + std::to_string(count) +
                                ": a scene switch keeps the devices; restart hapticd with this scene to change them");
  }
  for (std::size_t i = 0; i < count; ++i) {
    const std::string& next_model = scene::deviceAt(sc, i).model.name;
    const std::string& running_model = scene::deviceAt(running, i).model.name;
    if (next_model == running_model) continue;
    const std::string field = count == 1 ? "device.model" : "devices[" + std::to_string(i) + "].model";
    throw configError(path, field + " '" + next_model + "' differs from the running device's '" + running_model +
                                "': a scene switch keeps the device; restart hapticd with this scene to change it");
  }
  if (sc.rates.servo_hz != running.rates.servo_hz) {
    throw configError(path, "rates.servo_hz = " + numberText(sc.rates.servo_hz) + " differs from the running servo's " +
                                numberText(running.rates.servo_hz) +
                                " Hz: a scene switch keeps the servo rate; restart hapticd with this scene to change it");
  }
  return prepareScene(sc, path, specs, policy);
}

}  // namespace thx::srv
