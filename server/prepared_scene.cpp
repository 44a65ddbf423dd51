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

std::unique_ptr<PreparedScene> prepareScene(const scene::Scene& sc, const std::string& path,
                                            const dev::DeviceSpec& spec, const ScenePolicy& policy,
                                            std::shared_ptr<const MeshGeometry> mesh) {
  if (scene::deviceCount(sc) > 1) {
    std::string names;
    for (std::size_t i = 0; i < scene::deviceCount(sc); ++i) names += (i ? ", " : "") + scene::deviceAt(sc, i).name;
    throw configError(path, "devices: the scene lists " + std::to_string(scene::deviceCount(sc)) + " devices (" + names +
                                "); hapticd serves one device per scene so far: give one `device:`, or run one "
                                "hapticd per device");
  }
  if (sc.surface.mesh && policy.paper_loop_plane_hz)
    throw configError(path, "--paper-loop renders a plane per graphics frame; this scene's surface is a mesh "
                            "(surface.mesh): run it without --paper-loop");
  auto p = std::make_unique<PreparedScene>();
  p->path = path;
  p->warnings = sc.warnings;
  p->surface = scene::buildSceneSurface(sc);
  p->wiring = servoRigConfigFor(sc);
  RendererConfig& rc = p->wiring.renderer;
  if (policy.stiffness_fraction) rc.stiffness_n_per_m = *policy.stiffness_fraction * spec.max_stiffness_n_per_m;
  rc.crease_handling = policy.crease;
  p->wiring.passivity = policy.passivity;
  if (policy.paper_loop_plane_hz) applyPaperLoop(p->wiring, *policy.paper_loop_plane_hz);

  StabilityRequest sr;
  sr.stiffness_fraction = rc.stiffness_n_per_m / spec.max_stiffness_n_per_m;
  sr.virtual_damping_ns_per_m = rc.damping_ns_per_m;
  sr.period_s = p->wiring.period_s;
  sr.policy = policy.strict_stability ? BoundPolicy::Strict : BoundPolicy::Warn;
  p->budget = checkStabilityBudget(spec, sr);
  if (!p->budget.ok) {
    std::string all;
    for (const std::string& e : p->budget.errors) all += (all.empty() ? "" : "; ") + e;
    throw configError(path, all);
  }
  // The servo's passivity observer takes the renderer's stiffness as its K: checked here, off
  // the servo thread, as the controller's constructor would.
  servoPassivityConfig(spec, p->wiring.period_s, rc.stiffness_n_per_m, policy.passivity).validate();

  if (sc.surface.mesh) {
    try {
      p->mesh = mesh ? std::move(mesh) : buildMeshGeometry(sc);
    } catch (const scene::SceneError&) {
      throw;  // names the scene file, line and field already
    } catch (const thx::Error& e) {
      throw configError(path, std::string("surface.mesh: ") + e.what());
    }
    p->mesh_renderer = buildMeshRenderer(*p->mesh, p->surface.surface, rc);
  }
  p->fingerprint =
      p->mesh ? scene::meshSceneFingerprint(p->surface.fingerprint, p->mesh->scene_mesh) : p->surface.fingerprint;

  p->swap.surface = &p->surface.surface;
  p->swap.renderer = rc;
  p->swap.stored_energy_stiffness_n_per_m = rc.stiffness_n_per_m;
  p->swap.mesh = p->mesh_renderer.get();
  return p;
}

std::unique_ptr<PreparedScene> prepareSwitch(const std::string& path, const scene::Scene& running,
                                             const dev::DeviceSpec& spec, const ScenePolicy& policy) {
  const scene::Scene sc = scene::loadScene(path);
  if (sc.device.model.name != running.device.model.name) {
    throw configError(path, "device.model '" + sc.device.model.name + "' differs from the running device's '" +
                                running.device.model.name +
                                "': a scene switch keeps the device; restart hapticd with this scene to change it");
  }
  if (sc.rates.servo_hz != running.rates.servo_hz) {
    throw configError(path, "rates.servo_hz = " + numberText(sc.rates.servo_hz) + " differs from the running servo's " +
                                numberText(running.rates.servo_hz) +
                                " Hz: a scene switch keeps the servo rate; restart hapticd with this scene to change it");
  }
  return prepareScene(sc, path, spec, policy);
}

}  // namespace thx::srv
