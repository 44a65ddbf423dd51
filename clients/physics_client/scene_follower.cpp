#include "clients/physics_client/scene_follower.hpp"

#include <algorithm>
#include <cstdio>

#include "scenes/scene_loader.hpp"

namespace thx::physclient {

DriverOptions driverOptionsFor(const Options& o, const scene::Scene& scene) {
  DriverOptions d;
  d.rate_hz = o.rate_hz.value_or(scene.rates.physics_hz);
  d.pose_hz = o.pose_hz.value_or(scene.rates.visual_hz);
  d.contact_hz = std::min(d.rate_hz, o.contact_hz.value_or(scene.rates.audio_feed_hz));
  return d;
}

SceneFollower::SceneFollower(const Options& o)
    : options_(o),
      scenes_dir_(o.scenesDir()),
      file_(client::resolveSceneArgument(o.scene, scenes_dir_)),
      physics_(build(file_)),
      rates_(driverOptionsFor(o, physics_->scene())) {}

std::unique_ptr<PhysicsScene> SceneFollower::build(const std::string& file) const {
  const scene::Scene data = scene::loadScene(file);
  for (const std::string& w : data.warnings) std::fprintf(stderr, "physics-client: warning: %s\n", w.c_str());
  SimOptions so;
  so.pen = options_.pen;
  so.impact_min_speed_m_per_s = options_.impact_min_speed;
  so.pen_devices = pen_devices_;
  auto physics = std::make_unique<PhysicsScene>(data, so);
  for (const std::string& w : physics->warnings()) std::fprintf(stderr, "physics-client: warning: %s\n", w.c_str());
  return physics;
}

void SceneFollower::setPens(const std::vector<int>& devices) {
  pen_devices_ = devices;
  physics_->addPens(devices);
}

void SceneFollower::start(EventSink& sink) {
  sink_ = &sink;
  driver_ = std::make_unique<Driver>(*physics_, sink, rates_);
}

client::SceneIdentity SceneFollower::identity() const {
  return {physics_->sceneSurface().scene_name, physics_->sceneSurface().fingerprint};
}

bool SceneFollower::follow(const client::SceneIdentity& server, const std::string& server_label) {
  if (server == identity()) return false;
  std::string file;
  std::unique_ptr<PhysicsScene> next;
  try {
    file = client::resolveSceneName(server.name, scenes_dir_);
    next = build(file);
  } catch (const thx::Error& e) {
    throw thx::Error(thx::Error::Kind::Config,
                     server_label + " switched to scene '" + server.name + "', which this client cannot load from its " +
                         "scenes folder '" + scenes_dir_ + "': " + e.what() + "; " + server_label +
                         " found it in its own scenes folder, so the two folders differ: give this client the same "
                         "scene files");
  }
  // The same check as at the start (ClientApp::waitForServer), without --allow-different-scene:
  // a client that allows a difference keeps its own scene and never gets here.
  const client::SceneCheck check =
      client::checkScene(server, {next->sceneSurface().scene_name, next->sceneSurface().fingerprint},
                         /*allow_different_scene=*/false, server_label);
  if (!check.ok()) throw thx::Error(thx::Error::Kind::Config, check.message);

  if (driver_) {
    driver_->flush();  // the old scene's last contacts go out under the old scene
    earlier_ = has_earlier_ ? continuedRun(earlier_, driver_->summary()) : driver_->summary();
    has_earlier_ = true;
    driver_.reset();  // it refers to the old PhysicsScene
  }
  physics_ = std::move(next);
  file_ = file;
  rates_ = driverOptionsFor(options_, physics_->scene());
  if (sink_) driver_ = std::make_unique<Driver>(*physics_, *sink_, rates_);
  ++switches_;
  return true;
}

RunSummary SceneFollower::summary() const {
  RunSummary s = driver_ ? driver_->summary() : RunSummary{};
  if (!driver_) s.scene_name = physics_->sceneSurface().scene_name;
  if (has_earlier_) s = continuedRun(earlier_, s);
  for (std::size_t i = 0; i < s.pens.size() && i < pen_devices_.size(); ++i) s.pens[i].device = pen_devices_[i];
  s.scene_switches = switches_;
  return s;
}

}  // namespace thx::physclient
