#include "clients/audio/pen_meso_source.hpp"

#include <cmath>
#include <cstdlib>

namespace thx::audio {

namespace {
constexpr std::int64_t kReanchorNs = 5'000'000;
}

PenMesoSource::PenMesoSource(const tex::TextureMap& map, const TetMesh& slab, PenScrapeOptions options,
                             std::uint32_t generation, std::int64_t playout_delay_ns)
    : scrape_(map, slab, options), servo_hz_(options.servo_hz), generation_(generation), delay_ns_(playout_delay_ns) {}

void PenMesoSource::penContact(const thx_msgs::contact_t& c, std::int64_t receipt_ns, ExcitationSink& sink) {
  const std::int64_t utime_ns = c.utime * 1000;
  auto gridTime = [&](std::int64_t tick) {
    return anchor_ns_ + std::llround(double(tick - anchor_tick_) * 1e9 / servo_hz_);
  };
  if (!anchored_ || c.tick < anchor_tick_ || std::llabs(gridTime(c.tick) - utime_ns) > kReanchorNs) {
    anchored_ = true;
    anchor_tick_ = c.tick;
    anchor_ns_ = utime_ns;
  }
  ++ticks_;
  const ScrapeSample s{c.tick, c.in_contact != 0, {c.uv[0], c.uv[1]}};
  texels_ += scrape_.next(s, [&](const PenStrike& p) {
    ExcitationEvent e;
    e.time_ns = gridTime(p.tick) + delay_ns_;
    e.source_ns = utime_ns;
    e.receipt_ns = receipt_ns;
    e.generation = generation_;
    e.body = 0;
    e.node = p.node;
    e.impulse[2] = p.impulse_ns;
    sink.push(e);
  });
}

}  // namespace thx::audio
