#pragma once
// The feed side of the live client, without the network: the streams' messages handed to the
// scene's excitation sources, their events into a sink (the queue to the callback). Checks the
// batched CONTACT stream's continuity (batch seq, the server's dropped samples, a new server
// instance, a new subscription) and tells the sources when samples were lost; a tick is played
// once (resent batches and ticks already played are skipped). The live client calls it from the
// kit's callbacks; tests call it with recorded batches.
// It plays one pen: the device it follows (protocol 6). A server with several devices sends each
// device's batches, with a seq of its own, on one channel; the other devices' are counted and
// skipped before any continuity check, so they are neither gaps nor duplicates, and a sample of
// another pen never reaches the sources (which keep one pen's path).
#include <cstdint>
#include <vector>

#include <thx_msgs/contact_batch_t.hpp>

#include "clients/audio/synthesis/excitation.hpp"

namespace thx::audio {

// The sink the live client uses: the queue, with the events it could not take counted.
class QueueSink final : public ExcitationSink {
 public:
  explicit QueueSink(ExcitationQueue& queue) : queue_(queue) {}
  void push(const ExcitationEvent& event) override {
    if (!queue_.push(event)) ++dropped_;
  }
  std::uint64_t dropped() const { return dropped_; }

 private:
  ExcitationQueue& queue_;
  std::uint64_t dropped_ = 0;
};

struct FeedCounters {
  std::uint64_t batches = 0, samples = 0;
  std::uint64_t lost_batches = 0;     // gaps in the batch seq
  std::uint64_t server_dropped = 0;   // samples hapticd dropped (its ring overflowed)
  std::uint64_t restarts = 0;         // a new server_instance
  std::uint64_t duplicates = 0;       // batches whose ticks were all played already (resends)
  std::uint64_t resubscriptions = 0;  // the batch seq started again within one server instance
  std::uint64_t other_device = 0;     // batches of devices not followed: skipped, not in `batches`
  std::uint64_t physics_poses = 0, physics_contacts = 0, physics_impacts = 0;
};

class ExcitationFeed {
 public:
  // `device`: the index (hello_t.device_names) of the pen played; the same as the kit Client's
  // ClientOptions::device when the batches come through it.
  explicit ExcitationFeed(ExcitationSink& sink, int device = 0) : sink_(sink), device_(device) {}

  // The sources of the scene now playing (not owned; they must outlive their use here). A scene
  // switch replaces them all.
  void setSources(std::vector<ExcitationSource*> sources) { sources_ = std::move(sources); }
  void addSource(ExcitationSource* source) { sources_.push_back(source); }

  void contactBatch(const thx_msgs::contact_batch_t& batch, std::int64_t receipt_ns);
  void physicsPoses(const thx_msgs::physics_poses_t& m, std::int64_t receipt_ns);
  void physicsContacts(const thx_msgs::physics_contacts_t& m, std::int64_t receipt_ns);
  void physicsImpact(const thx_msgs::physics_impact_t& m, std::int64_t receipt_ns);

  const FeedCounters& counters() const { return counters_; }

 private:
  ExcitationSink& sink_;
  int device_;
  std::vector<ExcitationSource*> sources_;
  FeedCounters counters_;
  std::int64_t last_seq_ = 0, server_instance_ = 0, last_tick_ = 0;
  bool have_batch_ = false, have_tick_ = false;
};

}  // namespace thx::audio
