#pragma once
// One user-study session as the trial runner logs it and study-analyze reads it (docs/study.md):
// who, which study, the seed that drew the trials, the candidate surfaces, and one row per trial.
// Both studies share one row layout so one reader, one writer and one set of checks serve both;
// a study leaves the other study's columns empty.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/error.hpp"

namespace thx::study {

// A session file that breaks the format: the message names file, line and field.
class SessionError : public Error {
 public:
  explicit SessionError(const std::string& what) : Error(Kind::Config, what) {}
};

enum class Study {
  Identification,  // Study 1 (paper §5.2): which look goes with this sound, motion and feel
  ReliefVsNormal,  // Study 2 (paper §5.3): ratings of surfaces shown as relief or normal maps
};
std::string_view studyName(Study s);  // "identification", "relief-vs-normal"
std::optional<Study> parseStudy(std::string_view text);

enum class Representation { Normal, Relief, Mesh };
std::string_view representationName(Representation r);  // "normal", "relief", "mesh"
std::optional<Representation> parseRepresentation(std::string_view text);

// The cues a trial presented. Study 1 removes at most one; Study 2 keeps all three.
struct Cues {
  bool sound = true, ball = true, pen = true;
  bool operator==(const Cues&) const = default;
};
// "all cues", "no sound", "no ball", "no pen", "no sound+pen", ...
std::string cueCondition(const Cues& c);

// The rating columns, in file order. Study 1 asks ease and how much / how well each cue served;
// Study 2 asks realism, the three matches and overall quality.
enum class Rating : int {
  Ease, UseSound, UseBall, UsePen, AccSound, AccBall, AccPen,                   // Study 1
  Realism, MatchPhysics, MatchSound, MatchHaptics, Overall,                      // Study 2
  Count
};
constexpr int kRatingCount = static_cast<int>(Rating::Count);
struct RatingScale {
  std::string_view column;  // CSV column name
  int min, max;             // inclusive
  Study study;              // the study that asks it
};
const RatingScale& ratingScale(Rating r);

// A surface the participant may answer: its scene name and its sound family.
struct Candidate {
  std::string name, family;
  bool operator==(const Candidate&) const = default;
};

// "texhaptics " and the project's version (CMake's PROJECT_VERSION): what a runner of this
// build writes in the header's `software` line.
std::string softwareVersion();

struct SessionHeader {
  Study study = Study::Identification;
  std::string participant;
  std::uint64_t seed = 0;
  std::string software;  // the version of the software that ran the session
  std::vector<Candidate> surfaces;
  // Further "key: value" lines a runner adds (start time, scene folder...), kept in order.
  std::vector<std::pair<std::string, std::string>> extra;
  bool operator==(const SessionHeader&) const = default;

  const Candidate* find(std::string_view surface) const;
};

struct TrialRow {
  int trial = 0;  // 1, 2, ... in the order the participant met them
  std::string surface;
  Representation representation = Representation::Normal;
  Cues cues;
  std::string answer;            // Study 1: the surface chosen; Study 2: empty
  std::optional<bool> correct;   // Study 1: answer == surface
  std::optional<double> time_s;  // Study 1: from the trial's start to the confirmed answer
  std::array<std::optional<int>, kRatingCount> ratings{};
  bool operator==(const TrialRow&) const = default;

  std::optional<int> rating(Rating r) const { return ratings[static_cast<int>(r)]; }
  void setRating(Rating r, int value) { ratings[static_cast<int>(r)] = value; }
};

struct Session {
  std::string source;  // the file it was read from (for messages); not written
  SessionHeader header;
  std::vector<TrialRow> trials;
};

// Names, participant ids and header values are written unquoted, so they are restricted to
// letters, digits and "_-.+" (header values may also hold spaces, ':' and '/').
bool isToken(std::string_view s);
bool isHeaderValue(std::string_view s);
// Text from a file as an error message quotes it: printable ASCII kept, any other byte as \xNN (a
// NUL would end what() there and hide the rest of the message), at most 100 characters then "...".
std::string shownText(std::string_view s);

// The format's rules (docs/study.md §2). `where` names the place for messages ("s.csv:9", or
// "s.csv: header"). Throw SessionError.
void checkHeader(const SessionHeader& h, const std::string& where);

// The rules of one row and those between rows (trial numbers increase; Study 2 rates each surface
// once), checked row by row as a runner appends them or a reader meets them.
class RowRules {
 public:
  explicit RowRules(const SessionHeader& header) : header_(header) {}
  void check(const TrialRow& row, const std::string& where);

 private:
  const SessionHeader& header_;
  int last_trial_ = 0;
  std::vector<std::string> rated_;  // Study 2: surfaces rated so far
};

}  // namespace thx::study
