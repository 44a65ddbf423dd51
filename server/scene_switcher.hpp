#pragma once
// SceneSwitcher: hapticd's scene loads for a switch while the servo runs. A request (a client's
// server_command_t ACTION_LOAD_SCENE, through the publisher thread) names a scene; a worker
// thread of its own resolves the name in the scenes folder, loads and checks the scene exactly as
// a scene given at start (prepared_scene.hpp) and offers it to the servo through its handoff
// (Servo::surfaceSwap), one handoff per device. Each device's servo ramps its force down,
// retargets its renderer at a tick boundary, ramps it up and completes its handoff; only when
// every device has does the worker free the old scene.
// A scene that fails any check is refused with the loader's message and nothing changes: the old
// scene keeps running. One switch at a time: a request while one is loading is refused.
//
// Owns every scene the servo renders (the first one too), so it must outlive the servo's ticks.
// Threads: begin()/poll() from one thread (the publisher); the worker loads; the servo touches
// only the handoff.
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "rt/handoff.hpp"
#include "scenes/scene.hpp"
#include "server/prepared_scene.hpp"
#include "server/scene_loads.hpp"

namespace thx::srv {

struct SceneSwitcherOptions {
  std::string scenes_dir;  // where a scene's name is looked up: scenes_dir/NAME.yaml
  ScenePolicy policy;      // the command line's, as for the first scene
  bool quiet = false;      // no progress lines on stderr
  bool verbose = false;    // the stability budget's findings, explained (hapticd --verbose)
};

class SceneSwitcher final : public SceneLoads {
 public:
  // `running`: the scene the server started with (its devices, their models and the servo rate
  // stay); `first`: its prepared surface, which the servos render now. `handoffs[i]` and
  // `specs[i]`: device i's servo's (Servo::surfaceSwap) and spec, one per scene device.
  SceneSwitcher(std::vector<rt::Handoff<const SurfaceSwap>*> handoffs, scene::Scene running,
                std::vector<dev::DeviceSpec> specs, std::unique_ptr<PreparedScene> first,
                SceneSwitcherOptions options);
  // One device.
  SceneSwitcher(rt::Handoff<const SurfaceSwap>& handoff, scene::Scene running, const dev::DeviceSpec& spec,
                std::unique_ptr<PreparedScene> first, SceneSwitcherOptions options)
      : SceneSwitcher({&handoff}, std::move(running), {spec}, std::move(first), std::move(options)) {}
  ~SceneSwitcher() override;  // stops the worker; frees every scene (the servo must be stopped)
  SceneSwitcher(const SceneSwitcher&) = delete;
  SceneSwitcher& operator=(const SceneSwitcher&) = delete;

  std::optional<std::string> begin(const std::string& name) override;
  std::optional<Outcome> poll() override;

  std::uint32_t switchesOffered() const;  // scenes handed to the servo so far

 private:
  void work();
  void load(const std::string& name);
  void reclaim(std::unique_lock<std::mutex>& lock);  // frees the scene every servo has replaced

  const std::vector<rt::Handoff<const SurfaceSwap>*> handoffs_;
  const scene::Scene running_;
  const std::vector<dev::DeviceSpec> specs_;
  const SceneSwitcherOptions options_;

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::unique_ptr<PreparedScene> current_;  // the scene the servo renders (or rendered until its swap)
  std::unique_ptr<PreparedScene> offered_;  // handed to the servos, not yet known to be in use by all
  std::vector<bool> reclaimed_;             // per device: its servo is done with current_
  std::optional<std::string> job_;          // a name waiting for the worker
  bool loading_ = false;                    // the worker is on a job
  std::optional<Outcome> outcome_;          // of the last job, until polled
  std::uint32_t offers_ = 0;
  bool stop_ = false;
  std::thread worker_;
};

}  // namespace thx::srv
