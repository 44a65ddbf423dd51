#pragma once
// The sounding bodies of one scene as the audio callback plays them: a resonator bank per body
// and its mode shapes laid out node by node, so an event's modal impulse is one contiguous read.
// Built in the feed thread (it allocates), handed to the callback whole (rt::Handoff in
// LiveSynth), replaced whole on a scene switch. After construction strike, render and setBudget
// never allocate or lock.
//
// Events (excitation.hpp): an Impulse is projected from its node's row of shapes; a Point sums
// its nodes' rows with their shape-function weights, as ModalBody::gainsAt does, each mode's
// share times the Hertz pulse factor P(omega tau) (contact_pulse.hpp); a Micro event starts a
// force segment at a node or, with point nodes and weights, at a point (two objects rubbing): from
// the next sample on, every sample strikes force / fs (microForce's sample n,
// fractal_roughness.hpp, read from the scene's roughness profile) before it is rendered, so
// render() goes sample by sample while a segment lasts (as the offline render does).
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <array>
#include <memory>

#include "clients/audio/synthesis/excitation.hpp"
#include "clients/audio/synthesis/fractal_roughness.hpp"
#include "clients/audio/synthesis/resonator_bank.hpp"

namespace thx::audio {

struct SoundingBody {
  std::string name;
  std::vector<double> frequency_hz;  // ascending (the budget drops from the end: the highest)
  std::vector<double> decay_per_s;
  Eigen::MatrixXd shapes;            // mesh DOFs (3 node + axis) x modes: AudibleModes::shapes (listener included)
};

class SynthScene {
 public:
  // max_block: the longest block render() is given. Throws std::logic_error (a caller's mistake:
  // AudibleModes are in band) when a body's modes do not fit the bank (a frequency at or above
  // Nyquist, sizes that differ).
  // roughness: the profile Micro events read (none: they are refused).
  SynthScene(std::vector<SoundingBody> bodies, double sample_rate_hz, std::size_t max_block, std::uint32_t generation,
             std::shared_ptr<const RoughnessProfile> roughness = nullptr);

  std::uint32_t generation() const { return generation_; }
  std::size_t modes() const { return modes_; }
  std::size_t bodies() const { return voices_.size(); }
  const std::string& bodyName(std::size_t body) const { return voices_[body].name; }

  // Real-time side. strike: the event's modal impulse on its body, at the next sample render()
  // produces (a Micro event: its segment starts after that sample); false (nothing struck) for
  // an unknown body or node, a Micro event without a profile or with kMaxSegments running.
  // micro_samples: a Micro event's length in samples as the caller's clock places its two ends
  // (LiveSynth: sample of end_ns - sample of time_ns); < 0: from end_ns - time_ns.
  bool strike(const ExcitationEvent& event, std::int64_t micro_samples = -1);
  static constexpr std::size_t kMaxSegments = 16;
  std::size_t activeSegments() const { return segment_count_; }
  // Writes the sum of every body's modal displacements (with AudibleModes columns: what its
  // listener hears, docs/audio.md §9a).
  void render(std::span<float> out);
  // At most `total` modes in all, shared among the bodies in proportion to their modes.
  void setBudget(std::size_t total);
  std::size_t renderedModes() const;  // by the last render()
  // A muted scene (the scene's audio.mute): LiveSynth plays zeros while it is current and
  // strikes nothing. Set before the scene is offered.
  void setMuted(bool muted) { muted_ = muted; }
  bool muted() const { return muted_; }

 private:
  struct Voice {
    std::string name;
    ResonatorBank bank;
    std::vector<double> shapes;  // node-major: shapes[(3 node + axis) * modes + mode]
    std::vector<double> g;       // scratch modal impulse
    std::size_t nodes = 0;
    std::vector<double> omega;   // rad/s, for the Hertz pulse factor
  };
  // A Micro event's force segment in progress (at a node, or at a point: point_count > 0).
  struct Segment {
    std::uint16_t body = 0;
    std::int32_t node = 0;
    std::int32_t point_nodes[kMaxPointNodes] = {};
    double point_weights[kMaxPointNodes] = {};
    std::int32_t point_count = 0;
    double direction[3] = {0, 0, 0};
    std::size_t wait = 0, n = 0, count = 0, level = 0;
    double s0 = 0, s1 = 0, f0 = 0, f1 = 0;
  };
  void strikeNode(Voice& v, std::int32_t node, const double (&impulse)[3]);
  // v.g = the sum over the point's nodes of weight x (shape . impulse), ModalBody::gainsAt's order.
  void pointGains(Voice& v, const std::int32_t* nodes, const double* weights, std::int32_t count, const double (&impulse)[3]);
  bool validPoint(const Voice& v, const std::int32_t* nodes, std::int32_t count) const;
  void renderVoices(std::span<float> out);

  std::vector<Voice> voices_;
  std::shared_ptr<const RoughnessProfile> roughness_;
  double sample_rate_hz_;
  std::array<Segment, kMaxSegments> segments_{};
  std::size_t segment_count_ = 0;
  std::vector<float> scratch_;
  std::size_t modes_ = 0;
  std::uint32_t generation_;
  bool muted_ = false;
};

}  // namespace thx::audio
