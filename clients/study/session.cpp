#include "clients/study/session.hpp"

#include <algorithm>

#include "base/number_text.hpp"

namespace thx::study {

namespace {

constexpr std::array<RatingScale, kRatingCount> kScales{{
    {"ease", 1, 10, Study::Identification},
    {"use_sound", 1, 5, Study::Identification},
    {"use_ball", 1, 5, Study::Identification},
    {"use_pen", 1, 5, Study::Identification},
    {"acc_sound", 1, 10, Study::Identification},
    {"acc_ball", 1, 10, Study::Identification},
    {"acc_pen", 1, 10, Study::Identification},
    {"realism", 1, 10, Study::ReliefVsNormal},
    {"match_physics", 1, 10, Study::ReliefVsNormal},
    {"match_sound", 1, 10, Study::ReliefVsNormal},
    {"match_haptics", 1, 10, Study::ReliefVsNormal},
    {"overall", 1, 10, Study::ReliefVsNormal},
}};

[[noreturn]] void fail(const std::string& where, const std::string& field, const std::string& what) {
  throw SessionError(where + ": field '" + field + "': " + what);
}

bool tokenChar(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
         c == '.' || c == '+';
}

std::string surfaceList(const SessionHeader& h) {
  std::string s;
  for (const Candidate& c : h.surfaces) s += (s.empty() ? "" : ", ") + c.name;
  return s;
}

}  // namespace

std::string_view studyName(Study s) { return s == Study::Identification ? "identification" : "relief-vs-normal"; }

std::optional<Study> parseStudy(std::string_view text) {
  if (text == "identification") return Study::Identification;
  if (text == "relief-vs-normal") return Study::ReliefVsNormal;
  return std::nullopt;
}

std::string_view representationName(Representation r) {
  switch (r) {
    case Representation::Normal: return "normal";
    case Representation::Relief: return "relief";
    case Representation::Mesh: return "mesh";
  }
  return "?";
}

std::optional<Representation> parseRepresentation(std::string_view text) {
  for (Representation r : {Representation::Normal, Representation::Relief, Representation::Mesh}) {
    if (text == representationName(r)) return r;
  }
  return std::nullopt;
}

std::string cueCondition(const Cues& c) {
  std::string off;
  if (!c.sound) off += "sound";
  if (!c.ball) off += std::string(off.empty() ? "" : "+") + "ball";
  if (!c.pen) off += std::string(off.empty() ? "" : "+") + "pen";
  return off.empty() ? "all cues" : "no " + off;
}

std::string softwareVersion() { return std::string("texhaptics ") + THX_PROJECT_VERSION; }

const RatingScale& ratingScale(Rating r) { return kScales[static_cast<std::size_t>(r)]; }

const Candidate* SessionHeader::find(std::string_view surface) const {
  for (const Candidate& c : surfaces) {
    if (c.name == surface) return &c;
  }
  return nullptr;
}

std::string shownText(std::string_view s) {
  constexpr std::size_t kMaxShown = 100;
  std::string out;
  for (std::size_t i = 0; i < s.size() && i < kMaxShown; ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c >= 32 && c < 127) {
      out += static_cast<char>(c);
    } else {
      static const char* d = "0123456789abcdef";
      out += {'\\', 'x', d[c >> 4], d[c & 15]};
    }
  }
  return s.size() > kMaxShown ? out + "..." : out;
}

bool isToken(std::string_view s) { return !s.empty() && std::all_of(s.begin(), s.end(), tokenChar); }

bool isHeaderValue(std::string_view s) {
  return !s.empty() && s.front() != ' ' && s.back() != ' ' &&
         std::all_of(s.begin(), s.end(), [](char c) { return tokenChar(c) || c == ' ' || c == ':' || c == '/'; });
}

void checkHeader(const SessionHeader& h, const std::string& where) {
  if (!isToken(h.participant)) {
    fail(where, "participant", "expected letters, digits or _-.+, got '" + shownText(h.participant) + "'");
  }
  if (!isHeaderValue(h.software)) {
    fail(where, "software", "expected a version text (letters, digits, _-.+:/ and inner spaces), got '" +
                                shownText(h.software) + "'");
  }
  if (h.surfaces.empty()) fail(where, "surfaces", "expected at least one surface");
  for (std::size_t i = 0; i < h.surfaces.size(); ++i) {
    const Candidate& c = h.surfaces[i];
    if (!isToken(c.name) || !isToken(c.family)) {
      fail(where, "surfaces", "expected NAME=FAMILY of letters, digits or _-.+, got '" + shownText(c.name + "=" + c.family) + "'");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (h.surfaces[j].name == c.name) fail(where, "surfaces", "surface '" + c.name + "' is listed twice");
    }
  }
  for (const auto& [key, value] : h.extra) {
    if (!isToken(key) || !isHeaderValue(value)) {
      fail(where, shownText(key), "expected a key of letters, digits or _-.+ and a value of those, ':', '/' and "
                                  "inner spaces, got '" + shownText(key + ": " + value) + "'");
    }
  }
}

void RowRules::check(const TrialRow& row, const std::string& where) {
  const SessionHeader& h = header_;
  if (row.trial <= last_trial_) {
    fail(where, "trial", "expected a trial number above the previous row's " + std::to_string(last_trial_) + ", got " +
                             std::to_string(row.trial));
  }
  if (!h.find(row.surface)) {
    fail(where, "surface", "'" + row.surface + "' is not one of the header's surfaces (" + surfaceList(h) + ")");
  }
  for (int i = 0; i < kRatingCount; ++i) {
    const RatingScale& sc = kScales[static_cast<std::size_t>(i)];
    const std::optional<int>& v = row.ratings[static_cast<std::size_t>(i)];
    if (!v) continue;
    if (sc.study != h.study) {
      fail(where, std::string(sc.column), "study " + std::string(studyName(h.study)) + " leaves it empty, got " +
                                              std::to_string(*v));
    }
    if (*v < sc.min || *v > sc.max) {
      fail(where, std::string(sc.column), "expected a whole number in [" + std::to_string(sc.min) + ", " +
                                              std::to_string(sc.max) + "], got " + std::to_string(*v));
    }
  }
  if (row.time_s && !(*row.time_s >= 0 && *row.time_s < 1e9)) {
    fail(where, "time_s", "expected seconds >= 0, got " + numberText(*row.time_s));
  }
  if (h.study == Study::Identification) {
    if (row.answer.empty()) fail(where, "answer", "study identification needs the surface chosen");
    if (!h.find(row.answer)) {
      fail(where, "answer", "'" + row.answer + "' is not one of the header's surfaces (" + surfaceList(h) + ")");
    }
    if (!row.correct) fail(where, "correct", "study identification needs 1 or 0");
    if (*row.correct != (row.answer == row.surface)) {
      fail(where, "correct", std::string(*row.correct ? "1" : "0") + " contradicts answer '" + row.answer +
                                 "' for surface '" + row.surface + "'");
    }
    if (!row.time_s) fail(where, "time_s", "study identification needs the time to answer");
  } else {
    if (!row.answer.empty()) fail(where, "answer", "study relief-vs-normal leaves it empty, got '" + row.answer + "'");
    if (row.correct) fail(where, "correct", "study relief-vs-normal leaves it empty");
    for (int i = 0; i < kRatingCount; ++i) {
      const RatingScale& sc = kScales[static_cast<std::size_t>(i)];
      if (sc.study == Study::ReliefVsNormal && !row.ratings[static_cast<std::size_t>(i)]) {
        fail(where, std::string(sc.column), "study relief-vs-normal needs this rating");
      }
    }
    if (std::find(rated_.begin(), rated_.end(), row.surface) != rated_.end()) {
      fail(where, "surface", "'" + row.surface + "' was already rated in this session (each surface once, as "
                                                 "relief or as normal)");
    }
    rated_.push_back(row.surface);
  }
  last_trial_ = row.trial;
}

}  // namespace thx::study
