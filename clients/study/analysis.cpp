#include "clients/study/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace thx::study {

namespace {

std::vector<const Session*> ofStudy(const std::vector<Session>& sessions, Study study) {
  std::vector<const Session*> out;
  for (const Session& s : sessions) {
    if (s.header.study != study) continue;
    for (const Session* o : out) {
      if (o->header.participant == s.header.participant) {
        throw SessionError(s.source + ": participant '" + s.header.participant + "' already has a session of study " +
                           std::string(studyName(study)) + " in " + o->source);
      }
    }
    out.push_back(&s);
  }
  return out;
}

IdGroup& groupFor(std::vector<IdGroup>& groups, const std::string& label) {
  for (IdGroup& g : groups) {
    if (g.label == label) return g;
  }
  groups.push_back({label, "", 0, 0, {}, {}});
  return groups.back();
}

void count(IdGroup& g, const TrialRow& r) {
  ++g.trials;
  for (std::size_t i = 0; i < r.ratings.size(); ++i) {
    if (r.ratings[i]) g.ratings[i].push_back(double(*r.ratings[i]));
  }
  if (*r.correct) {
    ++g.correct;
    g.correct_times_s.push_back(*r.time_s);
  }
}

int cuesRemoved(const Cues& c) { return int(!c.sound) + int(!c.ball) + int(!c.pen); }

double mean(const std::vector<double>& v) { return summarize(v).mean; }

}  // namespace

double IdGroup::idRate() const {
  return trials == 0 ? std::numeric_limits<double>::quiet_NaN() : double(correct) / double(trials);
}

IdentificationResults analyzeIdentification(const std::vector<Session>& sessions) {
  IdentificationResults res;
  const std::vector<const Session*> own = ofStudy(sessions, Study::Identification);
  res.sessions = int(own.size());
  if (own.empty()) return res;
  const SessionHeader& first = own.front()->header;
  std::vector<std::string> names, families;
  for (const Candidate& c : first.surfaces) {
    names.push_back(c.name);
    if (std::find(families.begin(), families.end(), c.family) == families.end()) families.push_back(c.family);
    res.by_surface.push_back({c.name, c.family, 0, 0, {}, {}});
  }
  res.surfaces = ConfusionMatrix(names);
  res.families = ConfusionMatrix(families);
  // Fixed rows first, so tables keep the paper's order even when a condition has no trials.
  for (const char* l : {"all cues", "one cue removed"}) groupFor(res.by_condition, l);
  for (const char* l : {"all cues", "no sound", "no ball", "no pen"}) groupFor(res.by_cue, l);
  for (const Session* s : own) {
    std::vector<Candidate> a = s->header.surfaces, b = first.surfaces;
    std::sort(a.begin(), a.end(), [](auto& x, auto& y) { return x.name < y.name; });
    std::sort(b.begin(), b.end(), [](auto& x, auto& y) { return x.name < y.name; });
    if (a != b) {
      throw SessionError(s->source + ": header 'surfaces' differs from " + own.front()->source +
                         "'s (every identification session offers the same surfaces and families)");
    }
    for (const TrialRow& r : s->trials) {
      const int removed = cuesRemoved(r.cues);
      count(groupFor(res.by_condition, removed == 0   ? "all cues"
                                       : removed == 1 ? "one cue removed"
                                                      : std::to_string(removed) + " cues removed"),
            r);
      count(groupFor(res.by_cue, cueCondition(r.cues)), r);
      const auto it = std::find(names.begin(), names.end(), r.surface);
      count(res.by_surface[std::size_t(it - names.begin())], r);
      res.surfaces.add(r.surface, r.answer);
      res.families.add(first.find(r.surface)->family, first.find(r.answer)->family);
    }
  }
  res.by_cue_against_all.resize(res.by_cue.size());
  const std::vector<double>& all = res.by_cue[0].correct_times_s;
  for (std::size_t i = 1; i < res.by_cue.size(); ++i) {
    const std::vector<double>& t = res.by_cue[i].correct_times_s;
    res.by_cue_against_all[i] = {studentT(t, all), welchT(t, all), cohensD(t, all)};
  }
  return res;
}

RatingResults analyzeRatings(const std::vector<Session>& sessions) {
  RatingResults res;
  const std::vector<const Session*> own = ofStudy(sessions, Study::ReliefVsNormal);
  res.sessions = int(own.size());
  std::vector<Rating> ratings;
  for (int i = 0; i < kRatingCount; ++i) {
    if (ratingScale(Rating(i)).study == Study::ReliefVsNormal) ratings.push_back(Rating(i));
  }
  for (Rating r : ratings) res.paired.push_back({r, {}, {}, std::nullopt, std::nullopt});
  std::vector<std::string> surfaces;
  std::map<std::pair<std::string, int>, SurfaceRating> per_surface;
  for (const Session* s : own) {
    for (const Candidate& c : s->header.surfaces) {
      if (std::find(surfaces.begin(), surfaces.end(), c.name) == surfaces.end()) surfaces.push_back(c.name);
    }
    std::vector<std::vector<double>> relief(ratings.size()), normal(ratings.size());
    for (const TrialRow& row : s->trials) {
      if (row.representation == Representation::Mesh) {
        throw SessionError(s->source + ": trial " + std::to_string(row.trial) +
                           ": representation mesh: the relief-vs-normal analysis compares relief and normal maps only");
      }
      const bool is_relief = row.representation == Representation::Relief;
      for (std::size_t k = 0; k < ratings.size(); ++k) {
        const double v = double(*row.rating(ratings[k]));
        (is_relief ? relief : normal)[k].push_back(v);
        SurfaceRating& sr = per_surface[{row.surface, int(ratings[k])}];
        sr.surface = row.surface;
        sr.rating = ratings[k];
        (is_relief ? sr.relief : sr.normal).push_back(v);
      }
    }
    if (relief[0].empty() || normal[0].empty()) {
      res.unpaired_participants.push_back(s->header.participant);
      continue;
    }
    for (std::size_t k = 0; k < ratings.size(); ++k) {
      res.paired[k].relief.push_back(mean(relief[k]));
      res.paired[k].normal.push_back(mean(normal[k]));
    }
  }
  for (RatingComparison& c : res.paired) {
    c.paired = pairedT(c.relief, c.normal);
    c.d = cohensD(c.relief, c.normal);
  }
  for (const std::string& name : surfaces) {
    for (Rating r : ratings) {
      const auto it = per_surface.find({name, int(r)});
      if (it == per_surface.end()) continue;
      it->second.welch = welchT(it->second.relief, it->second.normal);
      res.by_surface.push_back(it->second);
    }
  }
  return res;
}

}  // namespace thx::study
