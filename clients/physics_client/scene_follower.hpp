#pragma once
// physics-client's scene, and following hapticd's (docs/physics.md, "Scene switches"): the
// simulation of one scene (its PhysicsScene and the Driver stepping it), built one way for the
// --scene at start and for every scene hapticd switches to, and the run summary over all of them.
// No LCM here: the online loop (physics_client.cpp) notices the switch in the hellos
// (thx::client::Client::sceneChanges), releases the pen force and calls follow(); tests call it
// directly.
#include <memory>
#include <string>
#include <vector>

#include "clients/physics_client/driver.hpp"
#include "clients/physics_client/options.hpp"
#include "clients/physics_client/physics_scene.hpp"
#include "thx_client/scene_check.hpp"

namespace thx::physclient {

// The driver's rates for `scene`: the scene's own (rates.physics_hz, visual_hz, audio_feed_hz)
// unless the command line set them; contacts never faster than steps.
DriverOptions driverOptionsFor(const Options& o, const scene::Scene& scene);

class SceneFollower {
 public:
  // Loads the --scene (a path, or a name in o.scenesDir()) and builds its simulation; the scene's
  // warnings go to stderr. Throws thx::Error naming the file (SceneLookupError, scene::SceneError,
  // tex::TextureError).
  explicit SceneFollower(const Options& o);
  SceneFollower(const SceneFollower&) = delete;
  SceneFollower& operator=(const SceneFollower&) = delete;

  // The devices whose pens are simulated, pen i following devices[i] (default {0}: one pen):
  // before start(). Adds the pens to the current scene and to every scene followed after it.
  void setPens(const std::vector<int>& devices);
  const std::vector<int>& penDevices() const { return pen_devices_; }

  // Starts stepping, events to `sink` (which must outlive this object). Once, before driver().
  void start(EventSink& sink);

  PhysicsScene& physics() { return *physics_; }
  Driver& driver() { return *driver_; }
  const DriverOptions& rates() const { return rates_; }
  const std::string& file() const { return file_; }   // the current scene's file
  const std::string& scenesDir() const { return scenes_dir_; }
  client::SceneIdentity identity() const;            // the current scene as hello_t names one
  int switches() const { return switches_; }

  // hapticd runs `server` now (server_label: its hello's server_name, for messages). Returns false
  // when that is the current scene already. Otherwise finds the name in scenesDir(), loads it,
  // checks its texture fingerprint against the server's, and replaces the simulation (the old
  // one's contacts flushed to the sink first); the new scene starts at simulated time 0 with its
  // own rates (rates()). The caller releases the pen force before (the sink sends forces).
  // Throws thx::Error (Config) and keeps the old simulation when the scene cannot be found or
  // loaded here (the message names the scene, the folder and why: the server found it in its own
  // folder, so the two folders differ), or its fingerprint differs (client::checkScene's message).
  bool follow(const client::SceneIdentity& server, const std::string& server_label = "hapticd");

  // Over the whole run: every scene's steps, times and events, the current scene's objects and
  // name, switches() followed.
  RunSummary summary() const;

 private:
  std::unique_ptr<PhysicsScene> build(const std::string& file) const;

  Options options_;
  std::string scenes_dir_;
  std::string file_;
  std::vector<int> pen_devices_ = {0};  // before physics_: build() reads it
  std::unique_ptr<PhysicsScene> physics_;
  DriverOptions rates_;
  EventSink* sink_ = nullptr;
  std::unique_ptr<Driver> driver_;
  RunSummary earlier_;  // the scenes before the current one
  bool has_earlier_ = false;
  int switches_ = 0;
};

}  // namespace thx::physclient
