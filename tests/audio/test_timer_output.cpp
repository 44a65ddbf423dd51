// The timer-driven callback that stands in for a sound device (clients/audio/live/audio_output.hpp):
// it calls the callback block after block with the block's size and a start time that grows,
// and its captured blocks carry what the callback wrote. Nothing about timing is asserted.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "clients/audio/live/audio_output.hpp"

namespace thx::audio::test_timer_output {
namespace {

TEST(TimerOutput, CallsTheCallbackBlockAfterBlockAndCapturesItsBlocks) {
  std::atomic<int> calls{0};
  std::atomic<bool> sizes_ok{true}, times_ok{true};
  std::int64_t last_start = 0;
  TimerOutput timer(48000.0, 64, [&](std::span<float> out, std::int64_t start_ns) {
    if (out.size() != 64) sizes_ok = false;
    if (start_ns <= last_start) times_ok = false;
    last_start = start_ns;
    const int k = calls.load();
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = float(k) + float(i) / 100.0f;
    calls.store(k + 1);
  }, 64);
  timer.start();
  for (int wait = 0; wait < 5000 && calls.load() < 5; ++wait) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  timer.stop();
  ASSERT_GE(calls.load(), 5);
  EXPECT_TRUE(sizes_ok.load());
  EXPECT_TRUE(times_ok.load());
  EXPECT_EQ(timer.blocks(), std::uint64_t(calls.load()));
  AudioBlock block;
  for (int k = 0; k < 5; ++k) {
    ASSERT_TRUE(timer.capture()->pop(block));
    ASSERT_EQ(block.frames, 64u);
    EXPECT_EQ(block.samples[0], float(k));
    EXPECT_EQ(block.samples[63], float(k) + 0.63f);
  }
}

TEST(TimerOutput, RejectsABlockLargerThanItsBuffer) {
  EXPECT_THROW(TimerOutput(48000.0, kMaxBlockFrames + 1, [](std::span<float>, std::int64_t) {}), std::logic_error);
  EXPECT_THROW(TimerOutput(48000.0, 0, [](std::span<float>, std::int64_t) {}), std::logic_error);
}

}  // namespace
}  // namespace thx::audio::test_timer_output
