// The live audio callback (LiveSynth::process) never allocates: events struck mid-block, late
// events, events of an old scene dropped, a new scene taken through the handoff, the budget shed
// and grown, a re-anchor after a stall, all with the allocation counter of the servo's tests.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "clients/audio/live_synth.hpp"
#include "tests/audio/live_fixtures.hpp"
#include "tests/support/allocation_counter.hpp"

namespace thx::audio {
namespace {

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
  synth.offerScene(std::make_unique<SynthScene>(std::vector<SoundingBody>{slab.body()}, 48000.0, 256, 1));
  std::vector<float> block(256);
  const std::int64_t period = 256 * 1'000'000'000LL / 48000;

  synth.process(block, 0);  // takes scene 1 (the handoff; first use)
  const long before = thx::test::t_allocations;
  std::int64_t t = 0;
  for (int k = 1; k < 200; ++k) {
    t += period;
    if (k == 120) t += 50 * period;  // a stall: the stream re-anchors, the block is late
    for (int j = 0; j < 4; ++j) ASSERT_TRUE(synth.queue().push(strike(t + j * period / 4, 1, 3 + j)));
    if (k % 10 == 0) {
      ASSERT_TRUE(synth.queue().push(strike(t - 5 * period, 1, 2)));  // late
    }
    clock.step_ns = (k / 20) % 2 ? period : 0;  // loaded, then light: shed and grow
    if (k == 150) {
      // The feed offers scene 2 (its allocation is the feed thread's, not counted here: this
      // test runs both on one thread, so it pauses the count around the feed's part).
      const long paused = thx::test::t_allocations;
      synth.offerScene(std::make_unique<SynthScene>(std::vector<SoundingBody>{slab.body()}, 48000.0, 256, 2));
      thx::test::t_allocations = paused;
    }
    if (k > 150) {
      ASSERT_TRUE(synth.queue().push(strike(t, 2, 5)));
    }
    synth.process(block, t);
  }
  EXPECT_EQ(thx::test::t_allocations - before, 0);
  const LiveSynthCounters& c = synth.counters();
  EXPECT_GT(c.events.load(), 0u);
  EXPECT_GT(c.late_events.load(), 0u);
  EXPECT_GT(c.stale_events.load(), 0u);
  EXPECT_EQ(c.scenes.load(), 2u);
  EXPECT_GE(c.reanchors.load(), 1u);
  EXPECT_LT(c.min_rendered_modes.load(), slab.modes.size());  // the budget was shed
}

}  // namespace
}  // namespace thx::audio
