#pragma once
// The physics client's streams live (an ExcitationSource), through the same PhysicsExcitation as
// the offline render (physics_excitation.hpp): impacts on both bodies with the Hertz contact time,
// Eq. 5 at every texel of a rolling or sliding object's texel path on a normal map, the change of
// its normal momentum on a relief map, each on the surface slab (body 0) and on the object (its
// SynthScene body, when it has audible modes). Each strike becomes a Point event: the point's
// element nodes and shape-function weights (ModalBody::weightsAt), the impulse in the body's
// frame, the contact time; the callback sums the gains as ModalBody::gainsAt does.
// Objects' frames come from the newest THX_PHYSICS_POSES at or before the event (the last 256
// messages are kept). Impacts with the pen strike the pen's body at its tip; the pen's lasting
// contacts are skipped (its scrape comes from hapticd's CONTACT). Two objects rubbing give Micro
// events at a point on each (the roughness force over the report's window, object_contact.hpp).
// Timing: a strike sounds at its time on the physics client's clock, as the offline render places
// it (an impact's utime plus half its contact time, a texel's entry time, a relief report's utime),
// plus the playout delay. A contacts message's texels lie up to its window (1 / contact rate,
// 1 ms by default) before its utime: a playout delay above that keeps them from being late.
#include <cstdint>
#include <deque>
#include <vector>

#include "clients/audio/synthesis/excitation.hpp"
#include "clients/audio/synthesis/physics_excitation.hpp"

namespace thx::audio {

class PhysicsSource final : public ExcitationSource {
 public:
  // `scene` must outlive this. object_bodies[k]: the SynthScene body of scene.objects[k] (-1:
  // silent); the surface is body 0; pen_body: the pen's (-1: silent). object_contacts.enabled
  // needs a SynthScene with a roughness profile (its Micro events are refused otherwise).
  PhysicsSource(const SoundingScene& scene, std::vector<int> object_bodies, std::uint32_t generation,
                std::int64_t playout_delay_ns, int pen_body = -1, ObjectContactOptions object_contacts = {});
  PhysicsSource(const PhysicsSource&) = delete;  // lookup_ points at this
  PhysicsSource& operator=(const PhysicsSource&) = delete;

  void physicsPoses(const thx_msgs::physics_poses_t& m, std::int64_t receipt_ns) override;
  void physicsContacts(const thx_msgs::physics_contacts_t& m, std::int64_t receipt_ns, ExcitationSink& sink) override;
  void physicsImpact(const thx_msgs::physics_impact_t& m, std::int64_t receipt_ns, ExcitationSink& sink) override;

  const PhysicsExcitationCounts& counts() const { return excitation_.counts(); }

 private:
  StrikeSink eventSink(std::int64_t source_ns, std::int64_t receipt_ns, ExcitationSink& sink);

  PhysicsExcitation excitation_;
  std::vector<int> object_bodies_;
  int pen_body_ = -1;
  std::uint32_t generation_;
  std::int64_t delay_ns_;
  std::deque<thx_msgs::physics_poses_t> poses_;
  PoseLookup lookup_;
};

}  // namespace thx::audio
