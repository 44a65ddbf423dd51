// The live audio callback (LiveSynth::process) never allocates: impulses struck mid-block, Point
// events with a Hertz pulse factor, micro-level force segments running across blocks on two
// bodies (at a node, and at a point as two objects rubbing give them), late events, events of an old scene dropped, a new scene taken through the handoff, the
// budget shed and grown, a re-anchor after a stall, all with the allocation counter of the
// servo's tests.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "clients/audio/live/live_synth.hpp"
#include "tests/audio/live_fixtures.hpp"
#include "tests/support/allocation_counter.hpp"

namespace thx::audio::test_live_no_allocation {
namespace {

// A Point event on the pen (body 1): its tip's element, a 50 µs Hertz pulse.
ExcitationEvent point(std::int64_t t_ns, std::uint32_t generation) {
  ExcitationEvent e;
  e.time_ns = t_ns;
  e.generation = generation;
  e.body = 1;
  e.kind = ExcitationKind::Point;
  e.point_count = 10;
  for (int c = 0; c < 10; ++c) {
    e.point_nodes[c] = c;
    e.point_weights[c] = 0.1;
  }
  e.impulse[0] = 1e-4;
  e.pulse_s = 5e-5;
  return e;
}

// A micro segment of 1.5 blocks on `body`.
ExcitationEvent micro(std::int64_t t_ns, std::int64_t period_ns, std::uint32_t generation, int body, int node) {
  ExcitationEvent e;
  e.time_ns = t_ns;
  e.end_ns = t_ns + 3 * period_ns / 2;
  e.generation = generation;
  e.body = std::uint16_t(body);
  e.node = node;
  e.kind = ExcitationKind::Micro;
  e.impulse[2] = body == 0 ? -1.0 : 1.0;
  e.s0 = 1e-3 * double(t_ns) / 1e9;
  e.s1 = e.s0 + 5e-4;
  e.f0 = 1.0;
  e.f1 = 1.2;
  return e;
}

ExcitationEvent strike(std::int64_t t_ns, std::uint32_t generation, int node) {
  ExcitationEvent e;
  e.time_ns = t_ns;
  e.source_ns = t_ns - 3'000'000;
  e.generation = generation;
  e.node = node;
  e.impulse[2] = 1e-4;
  return e;
}

TEST(LiveNoAllocation, TheCallbackAllocatesNothing) {
  const test::LiveSlab& slab = test::liveSlab();
  test::SteppingClock clock;
  LiveSynthOptions o;
  o.sample_rate_hz = 48000.0;
  LiveSynth synth(o, clock);
  const test::LivePen& pen = test::livePen();
  RoughnessOptions ro;
  ro.length = 1u << 12;
  const auto profile = std::make_shared<const RoughnessProfile>(ro);
  auto scene = [&](std::uint32_t generation) {
    return std::make_unique<SynthScene>(std::vector<SoundingBody>{slab.body(), pen.body()}, 48000.0, 256, generation, profile);
  };
  synth.offerScene(scene(1));
  std::vector<float> block(256);
  const std::int64_t period = 256 * 1'000'000'000LL / 48000;

  synth.process(block, 0);  // takes scene 1 (the handoff; first use)
  const long before = thx::test::t_allocations;
  std::int64_t t = 0;
  for (int k = 1; k < 200; ++k) {
    t += period;
    if (k == 120) t += 50 * period;  // a stall: the stream re-anchors, the block is late
    for (int j = 0; j < 4; ++j) {
      ASSERT_TRUE(synth.queue().push(micro(t + j * period / 4, period, 1, j % 2, j % 2 ? pen.tip : 3 + j)));
      ASSERT_TRUE(synth.queue().push(strike(t + j * period / 4, 1, 3 + j)));
    }
    if (k % 7 == 0) {
      ASSERT_TRUE(synth.queue().push(point(t + period / 3, 1)));
    }
    if (k % 5 == 0) {  // a micro segment at a point of the pen's tip element (two objects rubbing)
      ExcitationEvent rub = micro(t + period / 5, period, 1, 1, 0);
      const ExcitationEvent at = point(0, 1);
      rub.point_count = at.point_count;
      for (int c = 0; c < at.point_count; ++c) rub.point_nodes[c] = at.point_nodes[c], rub.point_weights[c] = at.point_weights[c];
      ASSERT_TRUE(synth.queue().push(rub));
    }
    if (k % 10 == 0) {
      ASSERT_TRUE(synth.queue().push(strike(t - 5 * period, 1, 2)));  // late
    }
    clock.step_ns = (k / 20) % 2 ? period : 0;  // loaded, then light: shed and grow
    if (k == 150) {
      // The feed offers scene 2 (its allocation is the feed thread's, not counted here: this
      // test runs both on one thread, so it pauses the count around the feed's part).
      const long paused = thx::test::t_allocations;
      synth.offerScene(scene(2));
      thx::test::t_allocations = paused;
    }
    if (k > 150) {
      ASSERT_TRUE(synth.queue().push(strike(t, 2, 5)));
      ASSERT_TRUE(synth.queue().push(micro(t, period, 2, 1, pen.tip)));
    }
    synth.process(block, t);
  }
  EXPECT_EQ(thx::test::t_allocations - before, 0);
  const LiveSynthCounters& c = synth.counters();
  EXPECT_GT(c.events.load(), 0u);
  EXPECT_EQ(c.bad_events.load(), 0u);  // every micro segment found room, every Point its nodes
  EXPECT_GT(c.late_events.load(), 0u);
  EXPECT_GT(c.stale_events.load(), 0u);
  EXPECT_EQ(c.scenes.load(), 2u);
  EXPECT_GE(c.reanchors.load(), 1u);
  EXPECT_LT(c.min_rendered_modes.load(), slab.modes.size() + pen.modes.size());  // the budget was shed
}

}  // namespace
}  // namespace thx::audio::test_live_no_allocation
