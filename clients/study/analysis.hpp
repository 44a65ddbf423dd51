#pragma once
// The numbers behind study-analyze's tables (docs/study.md §4): Study 1's identification rate,
// time of correct answers and confusions by condition, cue and surface; Study 2's ratings of
// relief against normal maps, paired within participants, and per surface.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "clients/study/session.hpp"
#include "clients/study/stats.hpp"

namespace thx::study {

// Trials of one group: how many, how many answered right, and the times of the right answers.
struct IdGroup {
  std::string label;
  std::string family;  // by surface only
  int trials = 0, correct = 0;
  std::vector<double> correct_times_s;
  std::array<std::vector<double>, kRatingCount> ratings;  // every rating given in these trials
  double idRate() const;  // correct / trials; NaN for no trials
  Summary time() const { return summarize(correct_times_s); }
};

// Correct-answer times of a condition against those with every cue (independent samples: each
// trial is one draw; the participant saw three trials of each).
struct TimeComparison {
  std::optional<TTest> student, welch;
  std::optional<double> d;
};

struct IdentificationResults {
  int sessions = 0;
  std::vector<IdGroup> by_condition;  // "all cues", "one cue removed", then any other count removed
  std::vector<IdGroup> by_cue;        // "all cues", "no sound", "no ball", "no pen", then others
  std::vector<TimeComparison> by_cue_against_all;  // index as by_cue; [0] (all cues) is empty
  std::vector<IdGroup> by_surface;    // the header's surface order
  ConfusionMatrix surfaces{{}};       // truth rows, answer columns
  ConfusionMatrix families{{}};       // the same by sound family (first-seen order)
};

struct RatingComparison {
  Rating rating = Rating::Overall;
  // Per participant: the mean of their ratings of relief surfaces and of normal surfaces.
  std::vector<double> relief, normal;
  std::optional<TTest> paired;  // relief - normal
  std::optional<double> d;      // Cohen's d, pooled SD of the two lists
};

struct SurfaceRating {
  std::string surface;
  Rating rating = Rating::Overall;
  std::vector<double> relief, normal;  // every participant's rating of this surface
  std::optional<TTest> welch;          // relief - normal, between participants
};

struct RatingResults {
  int sessions = 0;
  std::vector<RatingComparison> paired;            // one per Study 2 rating, file order
  std::vector<std::string> unpaired_participants;  // rated only one representation: left out of `paired`
  std::vector<SurfaceRating> by_surface;           // surfaces in header order, then ratings
};

// Throws SessionError when sessions disagree (another surface list, a participant twice) or a
// Study 2 row shows a mesh. Sessions of the other study are ignored.
IdentificationResults analyzeIdentification(const std::vector<Session>& sessions);
RatingResults analyzeRatings(const std::vector<Session>& sessions);

}  // namespace thx::study
