#include "clients/audio/live/live_synth.hpp"

#include <algorithm>
#include <cmath>

namespace thx::audio {

namespace {
void storeMax(std::atomic<std::int64_t>& a, std::int64_t v) {
  if (v > a.load(std::memory_order_relaxed)) a.store(v, std::memory_order_relaxed);
}
void add(std::atomic<std::uint64_t>& a, std::uint64_t v = 1) {
  a.store(a.load(std::memory_order_relaxed) + v, std::memory_order_relaxed);
}
}  // namespace

LiveSynth::LiveSynth(LiveSynthOptions options, rt::Clock& cost_clock)
    : options_(options),
      cost_clock_(cost_clock),
      queue_(options.queue_capacity),
      played_(options.played_capacity),
      budget_(0, options.budget) {
  due_.reserve(options.queue_capacity);  // process() inserts within this and never allocates
}

LiveSynth::~LiveSynth() = default;

void LiveSynth::offerScene(std::unique_ptr<SynthScene> scene) {
  if (!scene) return;
  newest_generation_.store(scene->generation(), std::memory_order_relaxed);
  waiting_ = std::move(scene);
  collect();
}

void LiveSynth::collect() {
  if (handoff_.reclaim()) {
    in_use_ = std::move(offered_);  // the one it replaced is freed here, outside the callback
  }
  if (waiting_ && handoff_.state() == rt::Handoff<SynthScene>::State::Idle) {
    offered_ = std::move(waiting_);
    handoff_.offer(offered_.get());
  }
}

bool LiveSynth::sceneCurrent() const {
  return !waiting_ && !offered_ && in_use_ && in_use_->generation() == newest_generation_.load(std::memory_order_relaxed);
}

void LiveSynth::takeEvents(std::int64_t horizon) {
  if (!scene_) return;  // events wait in the queue for their scene
  // A new scene: what was taken for an older one is stale.
  const auto old = std::remove_if(due_.begin(), due_.end(),
                                  [g = scene_->generation()](const ExcitationEvent& e) { return e.generation < g; });
  add(counters_.stale_events, std::uint64_t(due_.end() - old));
  due_.erase(old, due_.end());
  while (due_.size() < due_.capacity()) {
    const ExcitationEvent* e = queue_.front();
    if (!e || e->generation > scene_->generation()) break;  // its scene is not here yet
    const bool stale = e->generation < scene_->generation();  // dropped whenever it is due
    if (!stale && sampleOf(e->time_ns) >= horizon) break;     // beyond the window: waits in the queue
    ExcitationEvent next;
    queue_.pop(next);
    if (stale) {
      add(counters_.stale_events);
      continue;
    }
    // After every event due no later: one source's events keep their order, several sources'
    // (pens, the physics client) are merged by time.
    const auto at = std::upper_bound(due_.begin(), due_.end(), next.time_ns,
                                     [](std::int64_t t, const ExcitationEvent& d) { return t < d.time_ns; });
    due_.insert(at, next);
  }
}

std::int64_t LiveSynth::sampleOf(std::int64_t time_ns) const {
  return std::llround(double(time_ns - anchor_ns_) * options_.sample_rate_hz / 1e9);
}

std::int64_t LiveSynth::timeOf(std::int64_t sample) const {
  return anchor_ns_ + std::llround(double(sample) * 1e9 / options_.sample_rate_hz);
}

void LiveSynth::process(std::span<float> out, std::int64_t block_start_ns) {
  const std::int64_t t_start = cost_clock_.nowNs();
  if (SynthScene* next = handoff_.take()) {
    scene_ = next;
    handoff_.complete();
    budget_.reset(next->modes());
    next->setBudget(next->modes());
    add(counters_.scenes);
  }

  const std::int64_t n = std::int64_t(out.size());
  const std::int64_t reanchor = options_.reanchor_ns > 0 ? options_.reanchor_ns
                                                          : std::int64_t(2e9 * double(n) / options_.sample_rate_hz);
  const std::int64_t expire = std::llround(double(options_.expire_ns) * options_.sample_rate_hz / 1e9);
  bool late = false;
  if (!anchored_) {
    anchored_ = true;
    anchor_ns_ = block_start_ns;
    stream_pos_ = 0;
  } else {
    const std::int64_t expected = timeOf(stream_pos_);
    if (std::llabs(block_start_ns - expected) > reanchor) {
      late = block_start_ns > expected;
      anchor_ns_ = block_start_ns - std::llround(double(stream_pos_) * 1e9 / options_.sample_rate_hz);
      add(counters_.reanchors);
    }
  }
  if (late) add(counters_.late_blocks);

  if (scene_ && scene_->muted()) {
    // Exact silence, the old scene's ring cut with it. A muted scene has no sources, so what
    // waits in the queue is older scenes' (stale); a newer scene's events wait for it.
    while (const ExcitationEvent* e = queue_.front()) {
      if (e->generation > scene_->generation()) break;
      add(counters_.stale_events);
      ExcitationEvent stale;
      queue_.pop(stale);
    }
    add(counters_.stale_events, due_.size());  // taken before the mute: older scenes'
    due_.clear();
    std::fill(out.begin(), out.end(), 0.0f);
    stream_pos_ += n;
    add(counters_.blocks);
    add(counters_.samples, std::uint64_t(n));
    return;
  }

  takeEvents(stream_pos_ + n + std::llround(double(options_.order_window_ns) * options_.sample_rate_hz / 1e9));
  std::int64_t pos = 0;
  std::size_t done = 0;  // due_[0, done) are played or expired
  for (; done < due_.size(); ++done) {
    const ExcitationEvent* e = &due_[done];
    const std::int64_t sample = sampleOf(e->time_ns) - stream_pos_;
    if (sample >= n) break;  // a later block's
    if (sample < -expire) {
      add(counters_.expired_events);
      continue;
    }
    const std::int64_t at = std::max(sample, pos);
    if (at > pos) scene_->render(out.subspan(std::size_t(pos), std::size_t(at - pos)));
    pos = at;
    if (scene_->strike(*e, sampleOf(e->end_ns) - sampleOf(e->time_ns))) {
      add(counters_.events);
      if (sample < 0) add(counters_.late_events);
      PlayedEvent p{e->source_ns, e->receipt_ns, e->time_ns, block_start_ns, std::int32_t(at), sample < 0};
      if (!played_.push(p)) add(counters_.played_dropped);
    } else {
      add(counters_.bad_events);
    }
  }
  due_.erase(due_.begin(), due_.begin() + std::ptrdiff_t(done));
  if (pos < n) {
    if (scene_)
      scene_->render(out.subspan(std::size_t(pos)));
    else
      std::fill(out.begin() + pos, out.end(), 0.0f);
  }
  stream_pos_ += n;
  add(counters_.blocks);
  add(counters_.samples, std::uint64_t(n));

  if (scene_) {
    const std::uint64_t rendered = scene_->renderedModes();
    counters_.rendered_modes.store(rendered, std::memory_order_relaxed);
    if (rendered < counters_.min_rendered_modes.load(std::memory_order_relaxed))
      counters_.min_rendered_modes.store(rendered, std::memory_order_relaxed);
    const std::int64_t cost = cost_clock_.nowNs() - t_start;
    counters_.last_cost_ns.store(cost, std::memory_order_relaxed);
    storeMax(counters_.max_cost_ns, cost);
    if (options_.adapt_budget) {
      const std::int64_t period = std::llround(double(n) * 1e9 / options_.sample_rate_hz);
      scene_->setBudget(budget_.update(cost, period, late));
    }
    counters_.budget.store(budget_.current(), std::memory_order_relaxed);
  }
}

}  // namespace thx::audio
