// The per-block mode budget (clients/audio/live/mode_budget.hpp) as a pure policy, and in the callback
// (LiveSynth) with a fake clock whose block cost follows the modes synthesised: load sheds the
// highest modes, room brings them back, all deterministic.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "clients/audio/live/live_synth.hpp"
#include "clients/audio/live/mode_budget.hpp"
#include "tests/audio/live_fixtures.hpp"

namespace thx::audio::test_mode_budget {
namespace {

constexpr std::int64_t kPeriod = 1'000'000;  // 1 ms blocks

TEST(ModeBudget, StartsAtTheMaximumAndKeepsItUnderLightLoad) {
  ModeBudget b(100);
  EXPECT_EQ(b.current(), 100u);
  for (int k = 0; k < 50; ++k) EXPECT_EQ(b.update(kPeriod / 10, kPeriod, false), 100u);
  EXPECT_EQ(b.sheds(), 0u);
  EXPECT_EQ(b.grows(), 0u);
}

TEST(ModeBudget, ShedsInProportionToTheOverload) {
  ModeBudget b(100);  // shed above 0.5, to 0.8 of that: a load of 1.0 keeps 40 %
  EXPECT_EQ(b.update(kPeriod, kPeriod, false), 40u);
  // Load 0.6 at 40 modes: 40 * 0.4 / 0.6 = 26.67 -> 26.
  EXPECT_EQ(b.update(kPeriod * 6 / 10, kPeriod, false), 26u);
  EXPECT_EQ(b.sheds(), 2u);
}

TEST(ModeBudget, SheddingAlwaysDropsAtLeastOneModeAndStopsAtTheMinimum) {
  ModeBudgetOptions o;
  o.min_modes = 3;
  ModeBudget b(10, o);
  // Just over the threshold: the proportional rule keeps 10 * 0.4 / 0.51 = 7.8 -> 7.
  EXPECT_EQ(b.update(kPeriod * 51 / 100, kPeriod, false), 7u);
  for (int k = 0; k < 20; ++k) b.update(10 * kPeriod, kPeriod, false);
  EXPECT_EQ(b.current(), 3u);
}

TEST(ModeBudget, ALateBlockShedsAQuarterEvenWhenCheap) {
  ModeBudget b(100);
  EXPECT_EQ(b.update(kPeriod / 10, kPeriod, true), 75u);
  EXPECT_EQ(b.update(kPeriod / 10, kPeriod, true), 56u);
}

TEST(ModeBudget, GrowsBackAfterEnoughLightBlocksInARow) {
  ModeBudget b(80);  // grow step 0.125 * 80 = 10 after 16 light blocks
  b.update(kPeriod, kPeriod, false);
  ASSERT_EQ(b.current(), 32u);
  for (int k = 0; k < 15; ++k) EXPECT_EQ(b.update(kPeriod / 10, kPeriod, false), 32u);
  EXPECT_EQ(b.update(kPeriod / 10, kPeriod, false), 42u);
  // A block between the thresholds (0.25..0.5) restarts the count.
  for (int k = 0; k < 15; ++k) b.update(kPeriod / 10, kPeriod, false);
  b.update(kPeriod * 3 / 10, kPeriod, false);
  for (int k = 0; k < 15; ++k) EXPECT_EQ(b.update(kPeriod / 10, kPeriod, false), 42u);
  EXPECT_EQ(b.update(kPeriod / 10, kPeriod, false), 52u);
  for (int k = 0; k < 100; ++k) b.update(kPeriod / 10, kPeriod, false);
  EXPECT_EQ(b.current(), 80u);  // never above the maximum
  EXPECT_EQ(b.grows(), 5u);     // 32 -> 42 -> 52 -> 62 -> 72 -> 80
}

TEST(ModeBudget, ResetTakesANewMaximum) {
  ModeBudget b(50);
  b.update(kPeriod, kPeriod, false);
  b.reset(12);
  EXPECT_EQ(b.current(), 12u);
  EXPECT_EQ(b.maxModes(), 12u);
}

// The callback measures its own cost on the clock it is given; here a block costs the same per
// mode it synthesises, 0.8 of the block period (48 samples at 48 kHz = 1 ms) for all of them.
// Above 0.5 of the period the callback sheds the highest modes until the cost fits, and stays
// there; with the load gone it grows back to all of them.
TEST(ModeBudgetInCallback, FakeClockCostShedsTheHighestModesAndSettles) {
  const test::LiveSlab& slab = test::liveSlab();
  const std::size_t modes = slab.modes.size();
  ASSERT_GE(modes, 6u);
  test::SteppingClock clock;
  LiveSynthOptions o;
  o.sample_rate_hz = 48000.0;
  LiveSynth synth(o, clock);
  synth.offerScene(std::make_unique<SynthScene>(std::vector<SoundingBody>{slab.body()}, 48000.0, 48, 1));
  const std::int64_t per_mode_ns = 800'000 / std::int64_t(modes);  // all modes: 0.8 of the period
  std::vector<float> block(48);
  std::vector<std::size_t> rendered;
  for (int k = 0; k < 40; ++k) {
    const std::size_t budget = k == 0 ? modes : std::size_t(synth.counters().budget.load());
    clock.step_ns = std::int64_t(budget) * per_mode_ns;
    synth.process(block, 1'000'000 * std::int64_t(k));
    rendered.push_back(std::size_t(synth.counters().rendered_modes.load()));
  }
  EXPECT_EQ(rendered.front(), modes);  // the first block had them all
  const std::size_t settled = rendered.back();
  EXPECT_LT(settled, modes);
  EXPECT_GE(settled, 1u);
  // The cost at the settled budget is within the policy's band (below 0.5 of the period).
  EXPECT_LE(double(settled) * double(per_mode_ns), 0.5 * 1e6);
  EXPECT_EQ(settled, modes / 2);  // 0.8 -> 0.4 of the period in one step
  for (int k = 1; k < 40; ++k) EXPECT_EQ(rendered[std::size_t(k)], settled) << "block " << k;

  // Load gone (a free clock): the budget grows back to every mode.
  clock.step_ns = 0;
  for (int k = 40; k < 40 + 16 * 20; ++k) synth.process(block, 1'000'000 * std::int64_t(k));
  EXPECT_EQ(std::size_t(synth.counters().rendered_modes.load()), modes);
}

}  // namespace
}  // namespace thx::audio::test_mode_budget
