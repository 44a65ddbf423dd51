#include "clients/audio/live/pen_feeds.hpp"

#include "clients/audio/live/live_scene.hpp"

namespace thx::audio {

PenFeeds::PenFeeds(ExcitationSink& sink, std::optional<int> only_device)
    : only_device_(only_device), physics_(sink, -1) {
  for (int d = 0; d < kDevices; ++d) feeds_[std::size_t(d)] = std::make_unique<ExcitationFeed>(sink, d);
}

void PenFeeds::silence() {
  for (auto& f : feeds_) f->setSources({});
  physics_.setSources({});
}

void PenFeeds::setScene(const LiveScene& scene) {
  silence();
  const std::vector<ExcitationSource*> sources = scene.sourcePointers();  // empty when muted
  std::size_t next = 0;
  for (int device : scene.devices)
    if (next < sources.size()) setPen(device, {sources[next++]});
  setPhysics(std::vector<ExcitationSource*>(sources.begin() + std::ptrdiff_t(next), sources.end()));
}

void PenFeeds::contactBatch(const thx_msgs::contact_batch_t& b, std::int64_t receipt_ns) {
  if (b.device < 0 || b.device >= kDevices || (only_device_ && b.device != *only_device_)) {
    ++skipped_;
    return;
  }
  feed(b.device).contactBatch(b, receipt_ns);
}

FeedCounters PenFeeds::total() const {
  FeedCounters t = physics_.counters();
  for (const auto& f : feeds_) {
    const FeedCounters& c = f->counters();
    t.batches += c.batches;
    t.samples += c.samples;
    t.lost_batches += c.lost_batches;
    t.server_dropped += c.server_dropped;
    t.restarts += c.restarts;
    t.duplicates += c.duplicates;
    t.resubscriptions += c.resubscriptions;
  }
  t.other_device = skipped_;
  return t;
}

}  // namespace thx::audio
