#include "clients/study/simulated_session.hpp"

#include <cstdio>
#include <map>

#include "clients/study/participant_model.hpp"
#include "clients/study/session_csv.hpp"
#include "clients/study/surface_percept.hpp"
#include "clients/study/trial_plan.hpp"

namespace thx::study {
namespace {

const Cues kAllCues{};

SessionHeader headerFor(const StudyManifest& m, const SimulatedSessionOptions& o) {
  SessionHeader h = sessionHeaderFor(m, o.participant, o.seed);
  char jnd[32];
  std::snprintf(jnd, sizeof jnd, "%g", o.noise_jnd);
  h.extra.push_back({"participant_model", std::string("simulated noise ") + jnd + " JND"});
  return h;
}

// Renders each scene once with the pen and once without (lock-step, so a second run would give
// the same numbers); sound and ball are dropped from the first where a trial removes them.
class PerceptCache {
 public:
  Percept get(const std::string& scene, const Cues& cues) {
    const Cues render{true, true, cues.pen};
    const std::string key = scene + (cues.pen ? "|pen" : "|nopen");
    auto it = cache_.find(key);
    if (it == cache_.end()) it = cache_.emplace(key, measureSurface(scene, render)).first;
    return withoutSoundOrBall(it->second, cues);
  }

 private:
  std::map<std::string, Percept> cache_;
};

double answerPhase(const std::string& scene, const Cues& cues, int nexts, int trial) {
  const ButtonRun b = pressButton(scene, cues, nexts);
  if (!b.confirm_s || b.nexts != nexts)
    throw SessionError("trial " + std::to_string(trial) + ": the button protocol decoded " + std::to_string(b.nexts) +
                       " NEXT presses and " + (b.confirm_s ? "a" : "no") + " CONFIRM from the simulated hand's " +
                       std::to_string(nexts) + " short presses and one long press on " + scene);
  return *b.confirm_s;
}

}  // namespace

Session runSimulatedSession(const StudyManifest& m, const SimulatedSessionOptions& o) {
  Session session;
  session.source = o.out_csv;
  session.header = headerFor(m, o);
  SessionWriter writer(o.out_csv, session.header);
  SimulatedParticipant participant(o.seed ^ 0x5eed5eed5eed5eedULL, o.noise_jnd);
  PerceptCache cache;
  const int n = int(m.surfaces.size());
  for (const PlannedTrial& t : planSession(m, o.seed)) {
    const ManifestSurface& s = m.surfaces[std::size_t(t.surface)];
    TrialRow row;
    row.trial = t.trial;
    row.surface = s.name;
    row.cues = t.cues;
    const Percept presented = cache.get(t.scene, t.cues);
    row.representation = presented.representation;
    if (m.study == Study::ReliefVsNormal && presented.representation != t.representation)
      throw SessionError(m.source + ": surface '" + s.name + "': its " + std::string(representationName(t.representation)) +
                         " scene " + t.scene + " shows a " + std::string(representationName(presented.representation)) +
                         " map; expected a " + std::string(representationName(t.representation)) + " map");
    if (m.study == Study::Identification) {
      std::vector<Percept> expected;
      for (const ManifestSurface& c : m.surfaces) expected.push_back(cache.get(c.scene, kAllCues));
      const IdentificationAnswer a = participant.identify(presented, expected);
      const int nexts = ((a.answer - t.first_look) % n + n) % n;  // cycle from the first look to the answer
      row.answer = m.surfaces[std::size_t(a.answer)].name;
      row.correct = a.answer == t.surface;
      row.time_s = presented.explore_s + answerPhase(t.scene, t.cues, nexts, t.trial);
      row.setRating(Rating::Ease, a.ease);
      const Rating use[3] = {Rating::UseSound, Rating::UseBall, Rating::UsePen};
      const Rating acc[3] = {Rating::AccSound, Rating::AccBall, Rating::AccPen};
      for (int k = 0; k < 3; ++k) {
        if (a.use[std::size_t(k)]) row.setRating(use[k], *a.use[std::size_t(k)]);
        if (a.accuracy[std::size_t(k)]) row.setRating(acc[k], *a.accuracy[std::size_t(k)]);
      }
    } else {
      const SurfaceRatings r = participant.rate(presented, cache.get(s.relief, kAllCues), t.representation);
      row.time_s = presented.explore_s + answerPhase(t.scene, t.cues, 0, t.trial);
      row.setRating(Rating::Realism, r.realism);
      row.setRating(Rating::MatchPhysics, r.match_physics);
      row.setRating(Rating::MatchSound, r.match_sound);
      row.setRating(Rating::MatchHaptics, r.match_haptics);
      row.setRating(Rating::Overall, r.overall);
    }
    writer.append(row);
    session.trials.push_back(row);
  }
  return session;
}

}  // namespace thx::study
