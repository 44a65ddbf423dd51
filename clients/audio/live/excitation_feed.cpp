#include "clients/audio/live/excitation_feed.hpp"

namespace thx::audio {

void ExcitationFeed::contactBatch(const thx_msgs::contact_batch_t& b, std::int64_t receipt_ns) {
  if (b.device != device_) {  // another pen's: its seq and ticks are its own
    ++counters_.other_device;
    return;
  }
  ++counters_.batches;
  bool gap = false;
  if (have_batch_ && b.server_instance != server_instance_) {
    ++counters_.restarts;  // a new hapticd: its ticks start again
    gap = true;
    have_tick_ = false;
  } else if (have_batch_ && b.seq > last_seq_ + 1) {
    counters_.lost_batches += std::uint64_t(b.seq - last_seq_ - 1);
    gap = true;
  } else if (have_batch_ && b.seq <= last_seq_) {
    // A resend of a batch already played, or a new subscription whose seq starts again at 1
    // (the kit asked again after a silence): only newer ticks are played.
    if (b.samples.empty() || (have_tick_ && b.samples.back().tick <= last_tick_)) {
      ++counters_.duplicates;
      return;
    }
    ++counters_.resubscriptions;
    gap = true;
  }
  if (b.num_dropped > 0) {
    counters_.server_dropped += std::uint64_t(b.num_dropped);
    gap = true;
  }
  have_batch_ = true;
  last_seq_ = b.seq;
  server_instance_ = b.server_instance;
  if (gap)
    for (ExcitationSource* s : sources_) s->discontinuity();
  for (const thx_msgs::contact_t& c : b.samples) {
    if (have_tick_ && c.tick <= last_tick_) continue;  // already played
    have_tick_ = true;
    last_tick_ = c.tick;
    ++counters_.samples;
    for (ExcitationSource* s : sources_) s->penContact(c, receipt_ns, sink_);
  }
}

void ExcitationFeed::physicsPoses(const thx_msgs::physics_poses_t& m, std::int64_t receipt_ns) {
  ++counters_.physics_poses;
  for (ExcitationSource* s : sources_) s->physicsPoses(m, receipt_ns);
}

void ExcitationFeed::physicsContacts(const thx_msgs::physics_contacts_t& m, std::int64_t receipt_ns) {
  ++counters_.physics_contacts;
  for (ExcitationSource* s : sources_) s->physicsContacts(m, receipt_ns, sink_);
}

void ExcitationFeed::physicsImpact(const thx_msgs::physics_impact_t& m, std::int64_t receipt_ns) {
  ++counters_.physics_impacts;
  for (ExcitationSource* s : sources_) s->physicsImpact(m, receipt_ns, sink_);
}

}  // namespace thx::audio
