#include "clients/audio/live/physics_source.hpp"

#include <cmath>

namespace thx::audio {

namespace {
constexpr std::size_t kPosesKept = 256;
}

PhysicsSource::PhysicsSource(const SoundingScene& scene, std::vector<int> object_bodies, std::uint32_t generation,
                             std::int64_t playout_delay_ns, int pen_body, ObjectContactOptions object_contacts)
    : excitation_(scene, /*min_normal_dot=*/0.05, object_contacts),
      object_bodies_(std::move(object_bodies)),
      pen_body_(pen_body),
      generation_(generation),
      delay_ns_(playout_delay_ns) {
  lookup_ = [this](std::int64_t utime) -> const thx_msgs::physics_poses_t* {
    for (auto it = poses_.rbegin(); it != poses_.rend(); ++it)
      if (it->utime <= utime) return &*it;
    return nullptr;
  };
}

void PhysicsSource::physicsPoses(const thx_msgs::physics_poses_t& m, std::int64_t) {
  if (!poses_.empty() && m.utime < poses_.back().utime) poses_.clear();  // the physics client started again
  poses_.push_back(m);
  if (poses_.size() > kPosesKept) poses_.pop_front();
}

StrikeSink PhysicsSource::eventSink(std::int64_t source_ns, std::int64_t receipt_ns, ExcitationSink& sink) {
  return [=, this, &sink](const BodyStrike& s) {
    const int body = s.body == -1   ? 0
                     : s.body == -2 ? pen_body_
                                    : (std::size_t(s.body) < object_bodies_.size() ? object_bodies_[std::size_t(s.body)] : -1);
    if (body < 0) return false;
    const ModalBody::Weights w = s.modal->weightsAt(s.point);
    if (w.count == 0) return false;
    ExcitationEvent e;
    e.time_ns = s.utime * 1000 + std::llround(s.delay_s * 1e9) + delay_ns_;
    e.source_ns = source_ns;
    e.receipt_ns = receipt_ns;
    e.generation = generation_;
    e.body = std::uint16_t(body);
    e.kind = s.micro ? ExcitationKind::Micro : ExcitationKind::Point;
    if (s.micro) {  // a force segment (two objects rubbing): the callback reads the roughness
      e.end_ns = s.end_utime * 1000 + delay_ns_;
      e.s0 = s.s0, e.s1 = s.s1, e.f0 = s.f0, e.f1 = s.f1;
    }
    for (int i = 0; i < 3; ++i) e.impulse[i] = s.impulse[i];
    e.point_count = w.count;
    for (int c = 0; c < w.count; ++c) {
      e.point_nodes[c] = w.nodes[c];
      e.point_weights[c] = w.weights[c];
    }
    e.pulse_s = s.pulse_s;
    sink.push(e);
    return true;
  };
}

void PhysicsSource::physicsContacts(const thx_msgs::physics_contacts_t& m, std::int64_t receipt_ns, ExcitationSink& sink) {
  excitation_.contacts(m, lookup_, eventSink(m.utime * 1000, receipt_ns, sink));
}

void PhysicsSource::physicsImpact(const thx_msgs::physics_impact_t& m, std::int64_t receipt_ns, ExcitationSink& sink) {
  excitation_.impact(m, lookup_, eventSink(m.utime * 1000, receipt_ns, sink));
}

}  // namespace thx::audio
