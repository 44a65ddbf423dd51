#pragma once
// `physics-client --poses-csv FILE`: every dynamic object's pose and speed at the pose rate, in
// the world and in the surface's own frame (x, y along the plane, h above it), so a scene's
// trajectory can be read off a tilted plane without rotating it by hand. No LCM here.
#include <cstdio>
#include <string>

#include "clients/physics_client/driver.hpp"

namespace thx::physclient {

class PoseCsvSink final : public EventSink {
 public:
  // Opens FILE and writes the header (throws std::runtime_error naming the file if it cannot).
  explicit PoseCsvSink(const std::string& path);
  ~PoseCsvSink() override;
  PoseCsvSink(const PoseCsvSink&) = delete;
  PoseCsvSink& operator=(const PoseCsvSink&) = delete;
  void poses(const PhysicsScene& scene, std::int64_t ref_tick, const Eigen::Vector3d& pen_force_sent) override;

 private:
  std::string path_;
  std::FILE* out_ = nullptr;
};

// Hands every event to two sinks (LCM and a CSV file in one offline run).
class TeeSink final : public EventSink {
 public:
  TeeSink(EventSink& a, EventSink& b) : a_(a), b_(b) {}
  void penForce(const PhysicsScene& s, int pen, const PenForce& f, std::int64_t t) override {
    a_.penForce(s, pen, f, t), b_.penForce(s, pen, f, t);
  }
  void impacts(const PhysicsScene& s, const std::vector<Impact>& i) override { a_.impacts(s, i), b_.impacts(s, i); }
  void poses(const PhysicsScene& s, std::int64_t t, const Eigen::Vector3d& f) override { a_.poses(s, t, f), b_.poses(s, t, f); }
  void contacts(const PhysicsScene& s, const std::vector<LastingContact>& c, double w) override {
    a_.contacts(s, c, w), b_.contacts(s, c, w);
  }

 private:
  EventSink& a_;
  EventSink& b_;
};

}  // namespace thx::physclient
