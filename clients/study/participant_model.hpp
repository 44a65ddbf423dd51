#pragma once
// A simulated participant (docs/study.md §6): answers and rates from the features the trial's
// cues carry (surface_percept.hpp), blurred by seeded perceptual noise. Pure: no I/O, and the same
// seed gives the same answers.
//
// Study 1. The participant knows what each candidate look leads it to expect of every feature
// (the features of that candidate's scene with every cue on: perfect training). It perceives each
// feature the trial carries as value + noise · JND · N(0, 1), and answers the candidate nearest
// in JND units over the carried features: d_c = Σ ((perceived − expected_c) / JND)². Removing a
// cue removes its features from the sum, so candidates that differ only in that cue can no longer
// be told apart (within a sound family the sound carries nothing; surfaces of one family differ
// in texture, which the ball and the pen carry): accuracy falls.
//  - ease (1-10) = 1 + round(9 m), m = (d₂ − d₁)/(d₂ + d₁) the margin between the two nearest;
//  - use of a cue (1-5) = 1 + round(4 s_k / max s), s_k = Σ over its features of the candidates'
//    variance / JND²: how much the cue separates the candidates; removed cues are not rated;
//  - accuracy of a cue (1-10) = 1 + round(9 exp(−r_k / (2 n_k))), r_k the squared JND distance
//    of its perceived features from the chosen look's, n_k its feature count.
// Study 2. The look leads the participant to expect the relief version's features (the look
// shows the same bumps either way). Each match (physics = ball, sound, haptics = pen) is
// 1 + round(9 exp(−r_k / (2 n_k))) between the presented representation's perceived features and
// the relief version's; realism = 5 + 3 (if relief: parallax and self-occlusion) + round(noise);
// overall = the rounded mean of the four. A model, not a finding: it is there so the runner,
// the session files and the analysis can be tested end to end.
#include <array>
#include <cstdint>
#include <vector>

#include "clients/study/surface_percept.hpp"
#include "clients/study/trial_plan.hpp"

namespace thx::study {

struct IdentificationAnswer {
  int answer = 0;  // index of the chosen candidate
  int ease = 1;
  std::array<std::optional<int>, 3> use{}, accuracy{};  // sound, ball, pen
  std::vector<double> distances;                        // d_c per candidate
};

struct SurfaceRatings {
  int realism = 1, match_physics = 1, match_sound = 1, match_haptics = 1, overall = 1;
};

class SimulatedParticipant {
 public:
  SimulatedParticipant(std::uint64_t seed, double noise_jnd = 1.0) : rng_(seed), noise_(noise_jnd) {}

  // `expected[c]`: candidate c's features with every cue on. `presented`: the trial's, as its
  // cues leave them.
  IdentificationAnswer identify(const Percept& presented, const std::vector<Percept>& expected);

  SurfaceRatings rate(const Percept& presented, const Percept& relief_version, Representation shown);

 private:
  std::array<std::optional<double>, kFeatureCount> perceive(const Percept& p);
  StudyRng rng_;
  double noise_;
};

}  // namespace thx::study
