#pragma once
// The audio callback of the live client (docs/audio.md, "Live audio"): excitation events from the
// queue placed at their sample in the block, the scene's resonators rendered between them, the
// mode budget adapted to the callback's measured cost. process() never allocates, locks or waits.
//
// Time: the first block anchors the stream (sample 0 = its start time); block k starts at
// anchor + (samples so far) / fs, so events keep their spacing to the sample whatever the
// callback's jitter. Events are played in time order although they are queued out of it (each pen
// of several devices queues its batch's events in turn): the callback takes the queue's events due
// before the block's end plus `order_window_ns` into a time-ordered list (as long as the queue,
// reserved up front; equal times in queue order) and plays the block's from it. It stops at the
// first event beyond that window, so the events queued behind it come in order as long as no two
// events queued out of order lie further apart than the window (a batch's span plus a tick: the
// live client sets it from its batch rate). A block that starts more than `reanchor_ns` away from
// that (a stall, a device restart) re-anchors the stream at its own start time. An event whose
// sample is past sounds at the block's first sample (counted late), unless it is more than
// `expire_ns` late: then it is dropped (counted expired) rather than heard in a burst with others;
// an event beyond the block waits (in that list or the queue). While the current scene is muted
// (SynthScene::muted) every block is zeros and nothing is struck.
//
// Threads: one feed thread (queue().push, offerScene, collect, played().pop) and one audio thread
// (process). The counters may be read from any thread.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "clients/audio/live/mode_budget.hpp"
#include "clients/audio/synthesis/excitation.hpp"
#include "clients/audio/synthesis/synth_scene.hpp"
#include "rt/clock.hpp"
#include "rt/handoff.hpp"
#include "rt/spsc_ring.hpp"

namespace thx::audio {

struct LiveSynthOptions {
  double sample_rate_hz = 44100.0;
  std::size_t queue_capacity = 16384;    // events (about 16 s of a 1 kHz texel rate)
  std::size_t played_capacity = 65536;   // latency records kept for the feed thread
  std::int64_t reanchor_ns = 0;          // 0: two blocks
  std::int64_t expire_ns = 100'000'000;  // an event later than this is dropped (counted), not played
  std::int64_t order_window_ns = 20'000'000;  // events are put in time order this far beyond a block
  bool adapt_budget = true;
  ModeBudgetOptions budget;
};

// One event as it was played: what latency is measured from.
struct PlayedEvent {
  std::int64_t source_ns = 0, receipt_ns = 0, time_ns = 0;
  std::int64_t block_start_ns = 0;  // the first sample of the block that carried it
  std::int32_t offset = 0;          // its sample within the block
  bool late = false;                // its sample was already past
};

struct LiveSynthCounters {
  std::atomic<std::uint64_t> blocks{0}, samples{0};
  std::atomic<std::uint64_t> events{0}, late_events{0}, stale_events{0}, bad_events{0}, expired_events{0};
  std::atomic<std::uint64_t> late_blocks{0}, reanchors{0}, scenes{0}, played_dropped{0};
  std::atomic<std::uint64_t> budget{0}, rendered_modes{0}, min_rendered_modes{~std::uint64_t(0)};
  std::atomic<std::int64_t> last_cost_ns{0}, max_cost_ns{0};
};

class LiveSynth {
 public:
  // cost_clock measures the callback's own cost (the monotonic clock live, a fake one in tests).
  LiveSynth(LiveSynthOptions options, rt::Clock& cost_clock);
  ~LiveSynth();
  LiveSynth(const LiveSynth&) = delete;
  LiveSynth& operator=(const LiveSynth&) = delete;

  // ---- Feed thread ----
  ExcitationQueue& queue() { return queue_; }
  // The scene to play next (replaces one offered earlier that the callback has not taken).
  void offerScene(std::unique_ptr<SynthScene> scene);
  // Frees the scenes the callback is done with and offers a waiting one; call it now and then.
  void collect();
  // What process() played, oldest first (dropped and counted when full).
  rt::SpscRing<PlayedEvent>& played() { return played_; }
  // True once the callback plays the newest scene offered.
  bool sceneCurrent() const;

  // ---- Audio thread ----
  // The next block, whose first sample is heard at block_start_ns (CLOCK_MONOTONIC).
  void process(std::span<float> out, std::int64_t block_start_ns);

  const LiveSynthCounters& counters() const { return counters_; }
  const LiveSynthOptions& options() const { return options_; }

 private:
  std::int64_t sampleOf(std::int64_t time_ns) const;
  std::int64_t timeOf(std::int64_t sample) const;
  // The queue's events of the current scene due before sample `horizon` into due_, in time order.
  void takeEvents(std::int64_t horizon);


  LiveSynthOptions options_;
  rt::Clock& cost_clock_;
  ExcitationQueue queue_;
  rt::SpscRing<PlayedEvent> played_;
  LiveSynthCounters counters_;

  // Scenes: owned by the feed thread; the callback holds a plain pointer.
  rt::Handoff<SynthScene> handoff_;
  std::unique_ptr<SynthScene> in_use_, offered_, waiting_;
  std::atomic<std::uint32_t> newest_generation_{0};

  // Audio thread only.
  SynthScene* scene_ = nullptr;
  std::vector<ExcitationEvent> due_;  // taken from the queue, not yet played: ordered by time_ns
  ModeBudget budget_{0};
  bool anchored_ = false;
  std::int64_t anchor_ns_ = 0, stream_pos_ = 0;
};

}  // namespace thx::audio
