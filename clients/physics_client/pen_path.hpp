#pragma once
// Pen trajectories for deterministic runs without hapticd:
//  - a CSV file of world-frame tip positions (`t_s, x_m, y_m, z_m`);
//  - the scene's own hand script followed kinematically (the tip on the surface along the
//    script's presses and strokes; an approximation of what hapticd's simulated hand does);
//  - a recorded hapticd session (LCM log, lcm_io.hpp), converted to these samples.
// Linear interpolation between samples; before the first and after the last the end is held.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "clients/physics_client/physics_scene.hpp"

namespace thx::physclient {

struct PenSample {
  double t_s = 0.0;
  Eigen::Vector3d p_world = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_world = Eigen::Quaterniond::Identity();  // the device's (a recorded session's); else upright
  std::int64_t tick = -1;  // device tick when the sample came from hapticd
};

// Throws PenPathError with "FILE:LINE: FIELD: problem; expected ..., got '...'".
struct PenPathError : thx::Error {
  explicit PenPathError(const std::string& what) : thx::Error(Kind::Config, what) {}
};

// `#` comments and blank lines skipped; an optional header `t_s, x_m, y_m, z_m`; times >= 0 and
// strictly increasing; at least 2 rows; every value finite.
std::vector<PenSample> loadPenCsv(const std::string& path);
std::vector<PenSample> parsePenCsv(const std::string& text, const std::string& source);

// The scene's hand script (press, stroke, hold) as a kinematic tip path on the surface, sampled
// every dt_s. path_file steps are not supported, nor a mesh surface (PenPathError: hapticd's hand
// follows a mesh, this path the plane). Empty script: empty path.
std::vector<PenSample> penPathFromScript(const PhysicsScene& scene, double dt_s);

class PenPath {
 public:
  explicit PenPath(std::vector<PenSample> samples);  // non-empty, increasing times
  Eigen::Vector3d at(double t_s) const;
  Eigen::Quaterniond orientationAt(double t_s) const;  // slerp between samples
  std::int64_t tickAt(double t_s) const;  // tick of the sample at or before t (-1 if none)
  double duration() const { return samples_.back().t_s; }
  std::size_t size() const { return samples_.size(); }

 private:
  std::size_t indexAt(double t_s) const;
  // The samples around t and the later one's weight (the end sample twice, weight 0, outside).
  struct Bracket {
    const PenSample* a;
    const PenSample* b;
    double w;
  };
  Bracket bracketAt(double t_s) const;
  std::vector<PenSample> samples_;
  mutable std::size_t hint_ = 0;
};

}  // namespace thx::physclient
