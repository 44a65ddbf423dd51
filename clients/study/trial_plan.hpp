#pragma once
// The trials of one session, drawn from a seed (docs/study.md §5.2). Pure and deterministic: the
// same manifest and seed give the same plan on every machine (our own generator, not the
// standard library's distributions, whose results differ between implementations).
#include <cstdint>
#include <string>
#include <vector>

#include "clients/study/session.hpp"
#include "clients/study/study_manifest.hpp"

namespace thx::study {

// SplitMix64: small, fast, and fully specified, so a recorded seed replays everywhere.
class StudyRng {
 public:
  explicit StudyRng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  int below(int n);      // uniform in [0, n), n >= 1 (rejection, no modulo bias)
  double uniform();      // [0, 1)
  double gaussian();     // standard normal (Box-Muller)

 private:
  std::uint64_t state_;
};

struct PlannedTrial {
  int trial = 0;             // 1, 2, ...
  int surface = 0;           // index into the manifest's surfaces
  std::string scene;         // the scene file presented
  Representation representation = Representation::Normal;  // Study 2; Study 1: the scene's own
  Cues cues;
  int first_look = 0;        // Study 1: the candidate look shown first when the trial starts
};

// Study 1: six trials. 1-3 with every cue, then one each without sound, ball and pen in a random
// order; each trial's surface drawn uniformly from the candidates (repeats allowed: paper §5.2,
// "each trial draws a material at random"); the first look shown drawn uniformly too.
std::vector<PlannedTrial> planIdentification(const StudyManifest& m, std::uint64_t seed);

// Study 2: every surface once, in a random order; a random half shown as relief maps, the rest as
// normal maps (never both versions of one surface); all cues on.
std::vector<PlannedTrial> planReliefVsNormal(const StudyManifest& m, std::uint64_t seed);

std::vector<PlannedTrial> planSession(const StudyManifest& m, std::uint64_t seed);

}  // namespace thx::study
