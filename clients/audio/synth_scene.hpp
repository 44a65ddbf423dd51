#pragma once
// The sounding bodies of one scene as the audio callback plays them: a resonator bank per body
// and its mode shapes laid out node by node, so an event's modal impulse is one contiguous read.
// Built in the feed thread (it allocates), handed to the callback whole (rt::Handoff in
// LiveSynth), replaced whole on a scene switch. After construction strike, render and setBudget
// never allocate or lock.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "clients/audio/excitation.hpp"
#include "clients/audio/resonator_bank.hpp"

namespace thx::audio {

struct SoundingBody {
  std::string name;
  std::vector<double> frequency_hz;  // ascending (the budget drops from the end: the highest)
  std::vector<double> decay_per_s;
  Eigen::MatrixXd shapes;            // mesh DOFs (3 node + axis) x modes
};

class SynthScene {
 public:
  // max_block: the longest block render() is given. Throws std::invalid_argument when a body's
  // modes do not fit the bank (a frequency at or above Nyquist, sizes that differ).
  SynthScene(std::vector<SoundingBody> bodies, double sample_rate_hz, std::size_t max_block, std::uint32_t generation);

  std::uint32_t generation() const { return generation_; }
  std::size_t modes() const { return modes_; }
  std::size_t bodies() const { return voices_.size(); }
  const std::string& bodyName(std::size_t body) const { return voices_[body].name; }

  // Real-time side. strike: the event's modal impulse on its body, at the next sample render()
  // produces; false (nothing struck) for an unknown body or node.
  bool strike(const ExcitationEvent& event);
  // Writes the sum of every body's modal displacements.
  void render(std::span<float> out);
  // At most `total` modes in all, shared among the bodies in proportion to their modes.
  void setBudget(std::size_t total);
  std::size_t renderedModes() const;  // by the last render()

 private:
  struct Voice {
    std::string name;
    ResonatorBank bank;
    std::vector<double> shapes;  // node-major: shapes[(3 node + axis) * modes + mode]
    std::vector<double> g;       // scratch modal impulse
    std::size_t nodes = 0;
  };
  std::vector<Voice> voices_;
  std::vector<float> scratch_;
  std::size_t modes_ = 0;
  std::uint32_t generation_;
};

}  // namespace thx::audio
