#pragma once
// Shared by the benchmarks: a scene wired into the server's parts exactly as hapticd wires it
// (server/hapticd.cpp run()), device taps that record or replay a run, and small output helpers.
// Not real-time code: recording allocates.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "device/haptic_device.hpp"
#include "device/sim_phantom.hpp"
#include "scenes/scene.hpp"
#include "scenes/scene_surface.hpp"
#include "server/servo_rig.hpp"
#include "server/tick_record.hpp"
#include "textures/textured_surface.hpp"

namespace thx::bench {

// The source tree (scenes/ and benchmarks/scenes/ live there).
std::string sourceDir();

// A scene with its surface (scene::buildSceneSurface), optionally at another size than the file says.
struct SceneTexture {
  scene::Scene scene;
  scene::SceneSurface surface;
  const tex::TextureMap& map() const { return *surface.map; }
};
SceneTexture loadSceneTexture(const std::string& scene_path, int size_override = 0);

// The scene's surface over `map`; `relief` false reads the map as a normal map. A base of
// ServerRig, so that it exists before the servo.
struct PlacedSurface {
  PlacedSurface(const scene::Scene& sc, const tex::TextureMap& map, bool relief);
  tex::TexturedSurface surface;
};

// hapticd's server parts for one scene, wired by srv::ServoRig with hapticd's configuration
// (srv::servoRigConfigFor), crease handling as asked. reset() and drain() are srv::ServoRig's.
struct ServerRig : PlacedSurface, srv::ServoRig {
  ServerRig(const scene::Scene& sc, const tex::TextureMap& map, bool relief, bool crease, dev::HapticDevice& device);
};

// Forwards to a device and records every reading and command (preallocated by reserve()).
class TapDevice final : public dev::HapticDevice {
 public:
  explicit TapDevice(dev::HapticDevice& inner) : inner_(inner) {}
  const dev::DeviceSpec& spec() const override { return inner_.spec(); }
  dev::OutputMode outputMode() const override { return inner_.outputMode(); }
  void open() override { inner_.open(); }
  void close() override { inner_.close(); }
  dev::DeviceState read() override {
    const dev::DeviceState s = inner_.read();
    states.push_back(s);
    return s;
  }
  void write(const dev::DeviceCommand& c) override {
    commands.push_back(c);
    inner_.write(c);
  }
  std::vector<dev::DeviceState> states;
  std::vector<dev::DeviceCommand> commands;

 private:
  dev::HapticDevice& inner_;
};

// Replays recorded readings; commands go nowhere. Costs a copy per read.
class ReplayDevice final : public dev::HapticDevice {
 public:
  ReplayDevice(const dev::DeviceSpec& spec, const std::vector<dev::DeviceState>& states)
      : spec_(spec), states_(states) {}
  const dev::DeviceSpec& spec() const override { return spec_; }
  dev::OutputMode outputMode() const override { return dev::OutputMode::Force; }
  void open() override { next_ = 0; }
  void close() override {}
  dev::DeviceState read() override {
    const dev::DeviceState& s = states_[next_];
    next_ = next_ + 1 == states_.size() ? 0 : next_ + 1;
    return s;
  }
  void write(const dev::DeviceCommand& c) override { last_force_ = c.force_world_n; }
  std::size_t position() const { return next_; }
  const Eigen::Vector3d& lastForce() const { return last_force_; }

 private:
  dev::DeviceSpec spec_;
  const std::vector<dev::DeviceState>& states_;
  std::size_t next_ = 0;
  Eigen::Vector3d last_force_ = Eigen::Vector3d::Zero();
};

// One lock-step run of the scene's script (plus 0.5 s, as hapticd) through the full server,
// with the simulated device: what the device read, what the server wrote, and contact per tick.
struct Recording {
  std::vector<dev::DeviceState> states;
  std::vector<dev::DeviceCommand> commands;
  std::vector<char> in_contact;
  std::size_t first_contact = 0, last_contact = 0;  // tick indices; last < first if never in contact
  double contactFraction() const;
};
Recording recordRun(const scene::Scene& sc, const tex::TextureMap& map, bool relief, bool crease);

// Output helpers.
void writeTextFile(const std::string& path, const std::string& text);  // throws on failure
std::string fmt(const char* format, ...) __attribute__((format(printf, 1, 2)));
std::string machineDescription();  // CPU model, cores, kernel, clocksource (one line)
std::string isoTimeNow();

}  // namespace thx::bench
