#pragma once
// Meso impulses of the physics client's rolling and sliding objects (an ExcitationSource): each
// lasting surface contact of THX_PHYSICS_CONTACTS carries every texel its contact point crossed
// (with the texel's own normal and the point's velocity, world frame); at every texel entered,
// Eq. 5 (meso_impulses.hpp) with the object's mass gives the change of normal momentum from the
// texel it left, which strikes the surface slab (body 0) at the top-face node nearest the texel.
// The pen's entries are skipped (its impulses come from hapticd's CONTACT, PenMesoSource). A
// body missing from a message has lost contact: its walk starts again at its next contact.
// Timing: a texel sounds at the message's utime, minus how long before the message's last step
// the contact entered it, plus the window the message covers, plus the playout delay, so the
// texels of one message keep their spacing.
#include <cstdint>
#include <map>

#include "clients/audio/excitation.hpp"
#include "clients/audio/pen_scrape.hpp"

namespace thx::audio {

class PhysicsMesoSource final : public ExcitationSource {
 public:
  // map and slab must outlive this.
  PhysicsMesoSource(const tex::TextureMap& map, const TetMesh& slab, Eigen::Vector2d surface_size_m,
                    std::uint32_t generation, std::int64_t playout_delay_ns);

  void physicsContacts(const thx_msgs::physics_contacts_t& m, std::int64_t receipt_ns, ExcitationSink& sink) override;

  std::uint64_t texels() const { return texels_; }  // texels entered (impulses, zero ones included)

 private:
  struct Walk {
    std::int32_t i = 0, j = 0;
    Eigen::Vector3f normal{0, 0, 1};
  };
  const tex::TextureMap& map_;
  SlabTopFace top_;
  std::uint32_t generation_;
  std::int64_t delay_ns_;
  std::map<std::int32_t, Walk> walks_;  // by body_a
  std::uint64_t texels_ = 0;
};

}  // namespace thx::audio
