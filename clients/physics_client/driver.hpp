#pragma once
// Steps a PhysicsScene at a fixed rate and hands what it produces to a sink on the sink's own
// schedule: each pen's force every step (while non-zero, then one release), impacts when they
// happen, object poses at pose_hz, lasting contacts at contact_hz. The same driver runs behind
// LCM (physics_client.cpp) and offline in tests. No LCM here.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "clients/physics_client/physics_scene.hpp"

namespace thx::physclient {

class EventSink {
 public:
  virtual ~EventSink() = default;
  // Pen `pen`'s force, for its own device. By default force() below, which sees every pen's
  // alike: a sink that does not tell pens apart (a counter, a one-pen test) needs only that.
  virtual void penForce(const PhysicsScene& s, int /*pen*/, const PenForce& f, std::int64_t ref_tick) {
    force(s, f, ref_tick);
  }
  virtual void force(const PhysicsScene&, const PenForce&, std::int64_t /*ref_tick*/) {}
  virtual void impacts(const PhysicsScene&, const std::vector<Impact>&) {}
  virtual void poses(const PhysicsScene&, std::int64_t /*ref_tick*/, const Eigen::Vector3d& /*pen_force_sent*/) {}
  virtual void contacts(const PhysicsScene&, const std::vector<LastingContact>&, double /*window_s*/) {}
};

struct DriverOptions {
  double rate_hz = 1000.0;     // physics steps per simulated second
  double pose_hz = 60.0;       // object poses
  double contact_hz = 1000.0;  // lasting contacts (<= rate_hz)
};

// Another object this one touched, and when first (to the contact report's resolution).
struct Touch {
  std::string name;
  double first_s = 0.0;
};

struct ObjectSummary {
  std::string name;
  bool fixed = false;
  Eigen::Vector3d start_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_local = Eigen::Vector3d::Zero();  // surface frame: x, y along the plane, h above it (a mesh's frame)
  double start_h_m = 0.0;   // end_local's h at the start
  double max_rise_m = 0.0;  // highest h over the run above start_h_m (a lifted object's lift)
  double max_speed_m_per_s = 0.0;
  double end_speed_m_per_s = 0.0;
  std::vector<Touch> touched;  // other scene objects (not the plane, not the pen), in order of first touch
};

// One pen's share of a run (RunSummary::pens).
struct PenSummary {
  int device = 0;                        // the hapticd device it followed (its index in the hello)
  std::int64_t contact_steps = 0;        // steps with it touching an object
  std::int64_t force_steps = 0;          // steps with a non-zero force sent for it
  std::int64_t clamped_steps = 0;
  double max_force_raw_n = 0.0;
  double max_force_sent_n = 0.0;
  double mean_force_in_contact_n = 0.0;  // mean |sent| over its contact steps
  std::int64_t impacts = 0;              // impacts with it
};

struct RunSummary {
  std::string scene_name;               // the scene simulated (at the end, after switches)
  bool mesh_surface = false;            // its surface is a mesh: end_local is in its frame, not on a plane
  std::int64_t scene_switches = 0;      // online: hapticd's scene switches followed (a rebuild each)
  std::int64_t steps = 0;
  double sim_time_s = 0.0;
  // The pen fields count every pen together (pen-steps, the largest force of any): with one pen,
  // that pen's; each pen's own are in `pens`.
  std::int64_t pen_contact_steps = 0;   // steps with the pen touching an object
  std::int64_t force_steps = 0;         // steps with a non-zero force sent
  std::int64_t clamped_steps = 0;
  double max_force_raw_n = 0.0;         // largest |contact force on the pen|
  double max_force_sent_n = 0.0;        // largest |client force| (after scale and clamp)
  double mean_force_in_contact_n = 0.0; // mean |sent| over the pen-contact steps
  std::int64_t impacts = 0;
  std::int64_t pen_impacts = 0;
  std::int64_t contact_reports = 0;     // lasting-contact batches handed to the sink
  std::int64_t pose_reports = 0;
  std::vector<PenSummary> pens;         // one per pen, in pen order
  std::vector<ObjectSummary> objects;
  // Online runs only: what came from and went to hapticd (filled by physics-client's main).
  struct HapticdLink {
    bool online = false;
    std::int64_t device_states = 0;        // DEVICE_STATE messages received (of the device the kit follows)
    std::int64_t client_force_states = 0;  // of them, with FLAG_CLIENT_FORCE (hapticd applied a client force)
    double max_cmd_with_client_force_n = 0.0;
    std::int64_t forces_sent = 0;          // client_force_t messages sent (the release at exit included)
    std::int64_t stale_steps = 0;          // steps that reused the previous device state
    std::int64_t missed_steps = 0;         // grid points skipped after overruns (the pacer realigned)
  } hapticd;
};

class Driver {
 public:
  Driver(PhysicsScene& scene, EventSink& sink, const DriverOptions& options);
  double dt() const { return 1.0 / options_.rate_hz; }
  // One step with the (first) pen at `tip_world` (nullopt: the pen stays where it was, or parked).
  void step(const std::optional<Eigen::Vector3d>& tip_world, std::int64_t ref_tick = -1);
  // One step with pen i at pens[i] (pens beyond the list, and nullopt tips, stay where they were);
  // ref_tick: the device tick the tip is from, echoed in that pen's force (-1: none new).
  struct PenInput {
    std::optional<Eigen::Vector3d> tip_world;
    std::int64_t ref_tick = -1;
    std::optional<Eigen::Quaterniond> q_world;  // the device's orientation (PhysicsScene::setPenOrientation)
  };
  void step(const std::vector<PenInput>& pens);
  // Hands the contacts accumulated since the last report to the sink now.
  void flush();
  const RunSummary& summary() const { return summary_; }

 private:
  PhysicsScene& scene_;
  EventSink& sink_;
  DriverOptions options_;
  RunSummary summary_;
  void stepScene();
  void noteTouch(int id, int other, double t);
  struct PenState {
    double force_sum = 0.0;
    bool force_was_nonzero = false;
    std::int64_t last_ref_tick = -1;
  };
  std::vector<PenState> pens_;
  double force_sum_ = 0.0;
  double next_pose_t_ = 0.0, next_contact_t_ = 0.0, last_contact_t_ = 0.0;
};

// A run that went on in `current` after `earlier` (the scenes before a followed switch): counts
// and times added, maxima kept, the mean force weighted by contact steps; objects, scene name and
// the hapticd link are current's.
RunSummary continuedRun(const RunSummary& earlier, RunSummary current);

// Writes the summary as JSON (throws std::runtime_error naming the file if it cannot).
void writeSummaryJson(const std::string& path, const std::string& scene_file, const RunSummary& s);
void printSummary(std::FILE* out, const RunSummary& s);

}  // namespace thx::physclient
