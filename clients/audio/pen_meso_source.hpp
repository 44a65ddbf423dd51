#pragma once
// The pen's meso impulses live (an ExcitationSource): hapticd's batched CONTACT samples, one per
// servo tick, through the same PenScrape as the offline render, to impulse events on the surface
// slab (body 0). An event sounds at its tick's time plus the playout delay: tick times are taken
// on the servo's grid (anchor utime + ticks / servo rate), so the impulses keep the spacing the
// offline render gives them; the anchor is taken again when a sample's utime strays from the
// grid by more than 5 ms (missed ticks, a restart).
#include <cstdint>

#include "clients/audio/excitation.hpp"
#include "clients/audio/pen_scrape.hpp"

namespace thx::audio {

class PenMesoSource final : public ExcitationSource {
 public:
  // map and slab must outlive this.
  PenMesoSource(const tex::TextureMap& map, const TetMesh& slab, PenScrapeOptions options, std::uint32_t generation,
                std::int64_t playout_delay_ns);

  void penContact(const thx_msgs::contact_t& sample, std::int64_t receipt_ns, ExcitationSink& sink) override;
  void discontinuity() override { scrape_.reset(); }

  std::uint64_t ticks() const { return ticks_; }
  std::uint64_t texels() const { return texels_; }  // texels entered (impulses, zero ones included)

 private:
  PenScrape scrape_;
  double servo_hz_;
  std::uint32_t generation_;
  std::int64_t delay_ns_;
  bool anchored_ = false;
  std::int64_t anchor_tick_ = 0, anchor_ns_ = 0;
  std::uint64_t ticks_ = 0, texels_ = 0;
};

}  // namespace thx::audio
