#include "clients/audio/live/pen_source.hpp"

#include <cmath>
#include <cstdlib>
#include <numbers>

namespace thx::audio {

namespace {
constexpr std::int64_t kReanchorNs = 5'000'000;
}

PenSource::PenSource(const tex::TextureMap& map, const TetMesh& slab, PenScrapeOptions options, PenSourceBodies bodies,
                     std::uint32_t generation, std::int64_t playout_delay_ns)
    : scrape_(map, slab, options),
      bodies_(bodies),
      pen_direction_{std::sin(bodies.tilt_deg * std::numbers::pi / 180.0), 0.0,
                     std::cos(bodies.tilt_deg * std::numbers::pi / 180.0)},
      servo_hz_(options.servo_hz),
      generation_(generation),
      delay_ns_(playout_delay_ns) {}

void PenSource::penContact(const thx_msgs::contact_t& c, std::int64_t receipt_ns, ExcitationSink& sink) {
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
  auto event = [&](std::int64_t tick, int body, ExcitationKind kind) {
    ExcitationEvent e;
    e.time_ns = gridTime(tick) + delay_ns_;
    e.source_ns = utime_ns;
    e.receipt_ns = receipt_ns;
    e.generation = generation_;
    e.body = std::uint16_t(body);
    e.kind = kind;
    return e;
  };
  // The surface body gets -J along the node's direction (the slab: its +z; a mesh solid: the
  // node's outward normal), the pen +J along the surface normal (its frame).
  const ScrapeSites& sites = scrape_.sites();
  auto both = [&](ExcitationEvent e, int slab_node, double j) {
    e.node = slab_node;
    if (sites.onMesh())
      for (int i = 0; i < 3; ++i) e.impulse[i] = -j * sites.direction(slab_node)[i];
    else
      e.impulse[2] = -j;
    sink.push(e);
    if (bodies_.pen_body < 0) return;
    e.body = std::uint16_t(bodies_.pen_body);
    e.node = bodies_.tip_node;
    for (int i = 0; i < 3; ++i) e.impulse[i] = pen_direction_[i] * j;
    sink.push(e);
  };
  texels_ += scrape_.next(
      scrapeSample(c),
      [&](const PenStrike& p) { both(event(p.tick, 0, ExcitationKind::Impulse), p.node, p.impulse_ns); },
      [&](const PenMicroSegment& m) {
        if (!bodies_.micro || (m.f0 == 0.0 && m.f1 == 0.0)) return;  // no force: exactly silent
        ++micro_segments_;
        ExcitationEvent e = event(m.tick_a, 0, ExcitationKind::Micro);
        e.end_ns = gridTime(m.tick_b) + delay_ns_;
        e.s0 = m.s0, e.s1 = m.s1, e.f0 = m.f0, e.f1 = m.f1;
        both(e, m.node, 1.0);  // a unit direction: the callback scales it by the force / fs
      });
}

}  // namespace thx::audio
