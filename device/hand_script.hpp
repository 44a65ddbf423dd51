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
//  - hold: stay where the hand is (hovering, or where a move left it, with its push) for
//    duration_s.
//  - move (HandMove): from where the hand is to any point (x, y, height z) with a push vector;
//    no approach or ramp of its own (its duration is both). A contact step after it starts with
//    its transit, which ramps the push out; a script that ends pushing ramps it out over
//    force_ramp_s at its end. A move's z is the plane's: a height source (below) would override it
//    while "hovering", so hapticd refuses move steps on a mesh.
//  - The hand starts hovering above the first step's point (a contact step's start, a move's
//    target; (0, 0) if none) and, after the end, stays at its last target with zero push.
// During contact the target height is 0 (the surface plane): on a wall of stiffness K the
// steady contact force is push * K / (K + hand_stiffness), the hand's spring pulling back.
//
// A curved surface (a SurfaceHeight, surface_height.hpp, passed to sample()/sampleLocal()): the
// same steps, with (x, y) in the surface pose's frame and the push along its -z, but the target
// heights follow the surface: in contact (the force ramps and the body) z = h(x, y), the
// surface's height under the point seen from above (0 where nothing is under it: off the
// surface's footprint the hand presses toward the frame's z = 0); hovering (the start, transits,
// holds, the end) z = hover = hover_height_m + top(), above the surface's highest point, so a
// transit never cuts through it; descend and ascend blend between the two with the same
// minimum-jerk weight w as on the plane: z = hover + w (h - hover) at the step's point. The
// target velocity's z is the derivative of that: the blend's rate times (h - hover), plus, in
// contact, the rate of change of h along the horizontal motion (a central difference of h over
// +-kHeightSlopeStepM along the horizontal velocity, times the speed), so the hand's damper
// follows the surface instead of dragging. Timing, x, y, the push and the horizontal velocity
// are those of the plane. Without a height source (nullptr) the samples are the plane's, bit for
// bit as before height sources existed.
//
// sample() and sampleLocal() are real-time safe: binary search over prebuilt segments, no
// allocation, no exceptions; with a height source, at most three heightAt() calls per sample
// (none while hovering). Construction and loadPathCsv() allocate and may throw.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "base/error.hpp"
#include "device/surface_height.hpp"

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

// A move anywhere (issue 30: a hand that lifts the pen, or holds two pens against a box's sides):
// the target goes from where it is to `to_m` (plane-local x, y and height z above the plane) over
// duration_s, minimum-jerk, and the push goes from the one the hand has to `push_n` (a vector,
// plane-local, N) over the same time with the same minimum-jerk weight. The push then stays
// through holds and further moves until a contact step (its transit ramps it out) or the end.
struct HandMove {
  Eigen::Vector3d to_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d push_n = Eigen::Vector3d::Zero();
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

using HandStep = std::variant<HandPress, HandStroke, HandHold, HandPath, HandMove>;

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
  Eigen::Vector3d push_n = Eigen::Vector3d::Zero();  // along -normal (a move: any way), N
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

  // The half-width of the central difference that gives dh/dt in contact over a height source.
  static constexpr double kHeightSlopeStepM = 2e-4;

  // `height` (optional, not owned): the curved surface the contact follows (see the top of this
  // header); nullptr: the plane z = 0.
  HandTarget sampleLocal(double t_s, const SurfaceHeight* height = nullptr) const;
  HandTarget sample(double t_s, const Eigen::Isometry3d& plane_to_world, const SurfaceHeight* height = nullptr) const;

 private:
  struct Segment {
    enum class Kind { Blend, Stroke, Path };
    Kind kind = Kind::Blend;
    double t0_s = 0.0;
    double duration_s = 0.0;
    Eigen::Vector3d p0_m = Eigen::Vector3d::Zero();  // plane-local
    Eigen::Vector3d p1_m = Eigen::Vector3d::Zero();
    // The push, plane-local: Blend from push0 to push1 (along -z but after a move); Stroke push0
    // throughout.
    Eigen::Vector3d push0_n = Eigen::Vector3d::Zero();
    Eigen::Vector3d push1_n = Eigen::Vector3d::Zero();
    // Blend: how far the ends are in contact (1: on the surface, 0: hovering), blended as the
    // position; Stroke and Path: in contact throughout. Only a height source reads it.
    double c0 = 1.0;
    double c1 = 1.0;
    double speed_m_per_s = 0.0;  // Stroke
    double ramp_s = 0.0;         // Stroke
    std::size_t path_begin = 0;  // Path: samples_[path_begin, path_end)
    std::size_t path_end = 0;
  };

  // c0, c1: the ends' contact weights (Segment).
  void addBlend(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, double f0, double f1, double d_s, double c0,
                double c1);
  void addBlend(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& push0,
                const Eigen::Vector3d& push1, double d_s, double c0, double c1);
  // `push`: the push the hand has at the cursor (after a move), ramped out on the way.
  void addContactStep(const HandStep& step, Eigen::Vector3d& cursor, Eigen::Vector3d& push);
  // The plane's target, and the contact weight c and its rate dc/dt at that instant.
  HandTarget sampleSegment(const Segment& s, double t_s, double& c, double& c_rate) const;
  HandTarget samplePath(const Segment& s, double tau_s) const;
  // Moves a plane target onto the surface (the top of this header).
  void followSurface(HandTarget& target, double c, double c_rate, const SurfaceHeight& height) const;

  HandScriptOptions options_;
  std::vector<Segment> segments_;
  std::vector<double> starts_s_;  // segments_[i].t0_s, for the binary search
  std::vector<PathSample> samples_;
  Eigen::Vector3d start_m_ = Eigen::Vector3d::Zero();  // hover point before the first segment
  Eigen::Vector3d end_m_ = Eigen::Vector3d::Zero();    // hover point after the last
  double duration_s_ = 0.0;
};

}  // namespace thx::dev
