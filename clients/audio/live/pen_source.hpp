#pragma once
// The pen live (an ExcitationSource): hapticd's batched CONTACT samples, one per servo tick,
// through the same PenScrape as the offline render (pen_scrape.hpp), to events on both sides of
// the contact, as the offline render excites them (scrape_synthesis.hpp):
//  - each meso impulse J (Eq. 5 at a texel entered on a normal map, the contact normal's change on
//    a relief map): -J at the surface body's node (body 0) along its direction (the slab's +z, a
//    mesh solid's outward normal: scrape_sites.hpp), +J along the surface normal at the
//    pen's tip (the pen's body, its axis tilted from the normal);
//  - each segment in contact with a normal force: a Micro event on each of the two bodies (the
//    force of the roughness profile, rendered by the callback sample by sample).
// An event sounds at its tick's time plus the playout delay: tick times are taken on the servo's
// grid (anchor utime + ticks / servo rate), so the events keep the spacing the offline render
// gives them; the anchor is taken again when a sample's utime strays from the grid by more than
// 5 ms (missed ticks, a restart).
#include <cstdint>

#include "clients/audio/synthesis/excitation.hpp"
#include "clients/audio/synthesis/pen_scrape.hpp"

namespace thx::audio {

struct PenSourceBodies {
  int pen_body = -1;      // the pen's SynthScene body; -1: the slab alone sounds
  int tip_node = 0;       // the pen's tip node (penTipNode)
  double tilt_deg = 30.0; // its axis from the surface normal (the pen's frame: axis +z from the tip, tilted about y)
  bool micro = false;     // send the micro level (the SynthScene has the roughness profile)
};

class PenSource final : public ExcitationSource {
 public:
  // map and slab must outlive this.
  PenSource(const tex::TextureMap& map, const TetMesh& slab, PenScrapeOptions options, PenSourceBodies bodies,
            std::uint32_t generation, std::int64_t playout_delay_ns);

  void penContact(const thx_msgs::contact_t& sample, std::int64_t receipt_ns, ExcitationSink& sink) override;
  void discontinuity() override { scrape_.reset(); }

  std::uint64_t ticks() const { return ticks_; }
  std::uint64_t texels() const { return texels_; }  // meso impulses made (texels entered or relief ticks, zero ones included)
  std::uint64_t microSegments() const { return micro_segments_; }

 private:
  PenScrape scrape_;
  PenSourceBodies bodies_;
  double pen_direction_[3];  // the surface normal in the pen's frame
  double servo_hz_;
  std::uint32_t generation_;
  std::int64_t delay_ns_;
  bool anchored_ = false;
  std::int64_t anchor_tick_ = 0, anchor_ns_ = 0;
  std::uint64_t ticks_ = 0, texels_ = 0, micro_segments_ = 0;
};

}  // namespace thx::audio
