#pragma once
// Every pen live (issue 30; docs/audio.md §5b, "Every pen live"): one ExcitationFeed per device,
// each fed its own device's CONTACT batches (a device's batch seq and ticks are its own, so each
// keeps its own continuity) and driving that device's pen sources; the physics client's streams
// go to one more feed with the scene's other sources. Every feed pushes into the one sink, so
// every pen's events sound in the one SynthScene: the output is the sum of the pens' (modal
// synthesis is linear; tests/audio/test_live_pens.cpp). With `only_device` (--device N) that
// device's pen alone is played and the other devices' batches are counted and skipped.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "clients/audio/live/excitation_feed.hpp"
#include "scenes/scene.hpp"

namespace thx::audio {

struct LiveScene;

class PenFeeds {
 public:
  static constexpr int kDevices = int(scene::kMaxSceneDevices);  // device indices 0..kDevices-1

  PenFeeds(ExcitationSink& sink, std::optional<int> only_device);

  // The scene now playing: each of its pens' sources on its device's feed, its other sources on
  // the physics feed (a scene switch replaces them all; a device without a pen in it is silent).
  void setScene(const LiveScene& scene);
  void setPen(int device, std::vector<ExcitationSource*> sources) { feed(device).setSources(std::move(sources)); }
  void setPhysics(std::vector<ExcitationSource*> sources) { physics_.setSources(std::move(sources)); }
  void silence();  // no sources: nothing is excited (while a switched-to scene is being built)

  void contactBatch(const thx_msgs::contact_batch_t& batch, std::int64_t receipt_ns);
  void physicsPoses(const thx_msgs::physics_poses_t& m, std::int64_t t) { physics_.physicsPoses(m, t); }
  void physicsContacts(const thx_msgs::physics_contacts_t& m, std::int64_t t) { physics_.physicsContacts(m, t); }
  void physicsImpact(const thx_msgs::physics_impact_t& m, std::int64_t t) { physics_.physicsImpact(m, t); }

  // One device's feed's counters (zeros for a device never heard).
  const FeedCounters& counters(int device) const { return feeds_.at(std::size_t(device))->counters(); }
  // Every pen's counters summed, the physics feed's, and other_device: the batches skipped (of a
  // device not played, or an index outside 0..kDevices-1).
  FeedCounters total() const;

 private:
  ExcitationFeed& feed(int device) { return *feeds_.at(std::size_t(device)); }

  std::optional<int> only_device_;
  std::array<std::unique_ptr<ExcitationFeed>, kDevices> feeds_;  // by device index
  ExcitationFeed physics_;
  std::uint64_t skipped_ = 0;
};

}  // namespace thx::audio
