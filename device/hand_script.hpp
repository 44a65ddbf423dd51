#pragma once
// HandScript: what the simulated hand does, as a target the hand's impedance follows.
//
// Frames: steps are PLANE-LOCAL (x, y on the surface, z = height above it along the surface's
// outward normal). sampleLocal() answers in that frame; sample(t, plane_to_world) in the world.
//
// Timeline (every move is smooth, the target position never steps):
//  - Between contact steps the hand HOVERS at hover_height_m above the surface, no push.
//  - A contact step (press, stroke, path) is: transit at hover height to its start point
//    (minimum-jerk, average transit speed, at least min_transit_s; skipped if already there)
//    -> descend to the surface over approach_s -> ramp the push in over force_ramp_s -> the
//    step's body -> ramp the push out over force_ramp_s -> ascend over approach_s.
//  - press body: stay at the point with the full push for duration_s.
//  - stroke body: slide from -> to at speed; velocity ramps up and down with a raised cosine
//    over ramp = min(stroke_ramp_s, length / speed), so the body lasts length / speed + ramp.
//  - path body: the samples, linearly interpolated (position and force) over t_s in
//    [0, t_last]; before the first sample's time the hand waits at the first sample.
//  - hold: stay where the hand is (hovering) for duration_s.
//  - The hand starts hovering above the first contact step's start point ((0, 0) if none) and,
//    after the end, hovers at its last target with zero push.
// During contact the target height is 0 (the surface plane): on a wall of stiffness K the
// steady contact force is push * K / (K + hand_stiffness), the hand's spring pulling back.
//
// sample() and sampleLocal() are real-time safe: binary search over prebuilt segments, no
// allocation, no exceptions. Construction and loadPathCsv() allocate and may throw.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "base/error.hpp"

namespace thx::dev {

// A bad script step or path file. The message names the file, line and field when there is one:
//   FILE:LINE: FIELD: problem; expected WHAT, got 'VALUE'
class HandScriptError : public thx::Error {
 public:
  HandScriptError(const std::string& message, std::string file = {}, int line = 0, std::string field = {})
      : thx::Error(Kind::Config, message), file_(std::move(file)), line_(line), field_(std::move(field)) {}
  const std::string& file() const { return file_; }
  int line() const { return line_; }  // 1-based, 0 when not about a line
  const std::string& field() const { return field_; }

 private:
  std::string file_;
  int line_;
  std::string field_;
};

struct HandPress {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  double force_n = 0.0;
  double duration_s = 0.0;
};

struct HandStroke {
  Eigen::Vector2d from_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d to_m = Eigen::Vector2d::Zero();
  double speed_m_per_s = 0.0;
  double force_n = 0.0;
};

struct HandHold {
  double duration_s = 0.0;
};

struct PathSample {
  double t_s = 0.0;  // from the step's start
  Eigen::Vector2d p_m = Eigen::Vector2d::Zero();
  double force_n = 0.0;
};

struct HandPath {
  std::vector<PathSample> samples;  // t_s >= 0, strictly increasing, at least 2
  std::string source;               // file it came from, for messages
};

using HandStep = std::variant<HandPress, HandStroke, HandHold, HandPath>;

struct HandScriptOptions {
  double hover_height_m = 0.005;
  double approach_s = 0.2;              // descend / ascend
  double force_ramp_s = 0.1;            // push in / out
  double transit_speed_m_per_s = 0.1;   // average, hovering between contact steps
  double min_transit_s = 0.1;           // a short hop still takes this long
  double stroke_ramp_s = 0.1;           // stroke speed-up / slow-down
};

// The hand's target at one instant, in one frame (local or world, as returned).
struct HandTarget {
  Eigen::Vector3d p_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_m_per_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d push_n = Eigen::Vector3d::Zero();  // along -normal, magnitude = push force
  bool pressing = false;                              // push > 0: the sim's button 1
};

class HandScript {
 public:
  HandScript();  // empty: hover above the plane origin forever
  explicit HandScript(std::vector<HandStep> steps, HandScriptOptions options = {});

  // CSV `t_s, x_m, y_m, force_n` (docs/scenes.md): optional header line with exactly those
  // names, '#' starts a comment, blank lines skipped, t_s >= 0 strictly increasing, force_n
  // >= 0, every value finite, at least 2 rows. Throws HandScriptError naming file/line/field.
  static HandPath loadPathCsv(const std::string& path);

  double duration() const { return duration_s_; }
  const HandScriptOptions& options() const { return options_; }

  HandTarget sampleLocal(double t_s) const;
  HandTarget sample(double t_s, const Eigen::Isometry3d& plane_to_world) const;

 private:
  struct Segment {
    enum class Kind { Blend, Stroke, Path };
    Kind kind = Kind::Blend;
    double t0_s = 0.0;
    double duration_s = 0.0;
    Eigen::Vector3d p0_m = Eigen::Vector3d::Zero();  // plane-local
    Eigen::Vector3d p1_m = Eigen::Vector3d::Zero();
    double f0_n = 0.0;  // Blend: from f0 to f1; Stroke: f0 throughout
    double f1_n = 0.0;
    double speed_m_per_s = 0.0;  // Stroke
    double ramp_s = 0.0;         // Stroke
    std::size_t path_begin = 0;  // Path: samples_[path_begin, path_end)
    std::size_t path_end = 0;
  };

  void addBlend(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, double f0, double f1, double d_s);
  void addContactStep(const HandStep& step, Eigen::Vector3d& cursor);
  HandTarget sampleSegment(const Segment& s, double t_s) const;
  HandTarget samplePath(const Segment& s, double tau_s) const;

  HandScriptOptions options_;
  std::vector<Segment> segments_;
  std::vector<double> starts_s_;  // segments_[i].t0_s, for the binary search
  std::vector<PathSample> samples_;
  Eigen::Vector3d start_m_ = Eigen::Vector3d::Zero();  // hover point before the first segment
  Eigen::Vector3d end_m_ = Eigen::Vector3d::Zero();    // hover point after the last
  double duration_s_ = 0.0;
};

}  // namespace thx::dev
