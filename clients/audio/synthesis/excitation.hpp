#pragma once
// The live audio client's excitation interface (docs/audio.md, "Live audio"): what a contact does
// to the sounding bodies, as timestamped events from the thread that reads the streams (the feed)
// to the audio callback, through a lock-free single-producer single-consumer queue.
//
// To add an excitation: write an ExcitationSource, give it to the feed (LiveAudio::addSource) and push ExcitationEvents from
// its handlers. A source runs in the feed thread only (it may allocate there); the callback only
// reads the events. A body is an index into the SynthScene the events are played on (0 = the
// surface slab; LiveScene names the others); a node is a node of that body's mesh.
#include <cstdint>

#include <thx_msgs/contact_t.hpp>
#include <thx_msgs/physics_contacts_t.hpp>
#include <thx_msgs/physics_impact_t.hpp>
#include <thx_msgs/physics_poses_t.hpp>

#include "rt/spsc_ring.hpp"

namespace thx::audio {

enum class ExcitationKind : std::uint8_t {
  Impulse = 0,  // an impulse J at a node, applied at one sample (the pen's meso and relief impulses)
  Point = 1,    // an impulse J at a point of an element (its nodes' shape-function weights), applied
                // at one sample, each mode's share times the Hertz pulse factor of pulse_s
                // (contact_pulse.hpp; 0: an ideal impulse) (impacts, objects' texel paths)
  Micro = 2,    // the micro level's force over one servo segment (fractal_roughness.hpp's microForce
                // from s0, f0 to s1, f1) along `impulse` (a unit direction) at a node (the pen's
                // scrape) or, when point_count > 0, at a point (two objects rubbing), on the samples
                // after time_ns's up to end_ns's, rendered by the callback sample by sample
};

constexpr int kMaxPointNodes = 10;  // a Tet10's nodes

struct ExcitationEvent {
  std::int64_t time_ns = 0;      // when it sounds, CLOCK_MONOTONIC (the source's time + the playout delay)
  std::int64_t source_ns = 0;    // the source's own stamp (a CONTACT sample's utime), for latency
  std::int64_t receipt_ns = 0;   // when the feed received the message that caused it
  std::uint32_t generation = 0;  // the scene it belongs to (SynthScene::generation); others are dropped
  std::uint16_t body = 0;        // SynthScene body index (0 = the surface slab)
  ExcitationKind kind = ExcitationKind::Impulse;
  std::int32_t node = 0;             // node of the body's mesh
  double impulse[3] = {0, 0, 0};     // N s, in the body's mesh frame (Micro: a unit direction)
  // Point (and a Micro event at a point): the nodes and weights of the point (ModalBody::weightsAt),
  // the contact time.
  std::int32_t point_nodes[kMaxPointNodes] = {};
  double point_weights[kMaxPointNodes] = {};
  std::int32_t point_count = 0;
  double pulse_s = 0.0;
  // Micro: the segment's end, travelled distance (m) and normal force (N) at both ends.
  std::int64_t end_ns = 0;
  double s0 = 0.0, s1 = 0.0, f0 = 0.0, f1 = 0.0;
};

// Feed thread -> audio callback. Events of one producer are in time order. A full queue drops the
// new event and counts it (the callback is stalled; the feed must not wait for it).
using ExcitationQueue = rt::SpscRing<ExcitationEvent>;

// Where a source's events go (the queue in the live client, a vector in tests).
class ExcitationSink {
 public:
  virtual ~ExcitationSink() = default;
  virtual void push(const ExcitationEvent& event) = 0;
};

// One kind of excitation, fed by the streams. Handlers run in the feed thread; receipt_ns is the
// client's CLOCK_MONOTONIC at receipt. A source is built for one scene (SynthScene::generation)
// and replaced whole on a scene switch.
class ExcitationSource {
 public:
  virtual ~ExcitationSource() = default;
  // One servo tick of the pen (hapticd's batched CONTACT: every tick, oldest first).
  virtual void penContact(const thx_msgs::contact_t& /*sample*/, std::int64_t /*receipt_ns*/, ExcitationSink& /*sink*/) {}
  // The physics client's poses (an object's frame at its contacts), lasting contacts (with their
  // texel paths) and impacts.
  virtual void physicsPoses(const thx_msgs::physics_poses_t& /*m*/, std::int64_t /*receipt_ns*/) {}
  virtual void physicsContacts(const thx_msgs::physics_contacts_t& /*m*/, std::int64_t /*receipt_ns*/,
                               ExcitationSink& /*sink*/) {}
  virtual void physicsImpact(const thx_msgs::physics_impact_t& /*m*/, std::int64_t /*receipt_ns*/,
                             ExcitationSink& /*sink*/) {}
  // Samples were lost (a gap in the batches): forget the walk so far, make no impulse across it.
  virtual void discontinuity() {}
};

}  // namespace thx::audio
