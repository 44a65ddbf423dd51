// The simulated participant (docs/study.md §6): what each cue carries, measured on the servo rig;
// answers that use only the cues left on, so removing a cue lowers accuracy, as the model
// predicts; ratings on their scales; the same seed, the same answers.
#include <gtest/gtest.h>

#include "clients/study/participant_model.hpp"
#include "clients/study/study_manifest.hpp"

namespace thx::study::test_participant_model {
namespace {

const std::string kIdent = THX_TEST_DATA_DIR "/study/identification/manifest.yaml";

#ifndef THX_STUDY_MODEL_SLOW
TEST(SurfacePercept, RemovedCuesCarryNothing) {
  const StudyManifest m = loadManifest(kIdent);
  const std::string scene = m.surfaces[0].scene;
  const Percept all = measureSurface(scene, Cues{});
  for (int f = 0; f < kFeatureCount; ++f) EXPECT_TRUE(all.features[std::size_t(f)]) << "feature " << f;
  EXPECT_EQ(all.representation, Representation::Relief);
  EXPECT_GT(all.explore_s, 1.5);
  EXPECT_GT(*all.features[kPenLateral], -1.0);  // the lateral force is above a tenth of the normal

  const Percept no_sound = measureSurface(scene, Cues{false, true, true});
  EXPECT_FALSE(no_sound.features[kSoundPitch]);
  EXPECT_FALSE(no_sound.features[kSoundRing]);
  EXPECT_EQ(no_sound.features[kPenLateral], all.features[kPenLateral]);  // lock-step: the same run
  // Without the pen's force the servo renders (nearly) nothing: no feature, measured.
  const Percept no_pen = measureSurface(scene, Cues{true, true, false});
  EXPECT_FALSE(no_pen.features[kPenLateral]);
  EXPECT_FALSE(no_pen.features[kPenNormalVar]);
  EXPECT_EQ(no_pen.features[kBallShake], all.features[kBallShake]);

  // What the simulated session derives instead of rendering again (lock-step: the same numbers).
  const auto same = [](const Percept& a, const Percept& b) { return a.features == b.features; };
  EXPECT_TRUE(same(withoutSoundOrBall(all, Cues{false, true, true}), no_sound));
  const Percept no_ball = withoutSoundOrBall(all, Cues{true, false, true});
  EXPECT_FALSE(no_ball.features[kBallShake]);
  EXPECT_FALSE(no_ball.features[kBallSlip]);
  EXPECT_EQ(no_ball.features[kSoundPitch], all.features[kSoundPitch]);
}

TEST(SurfacePercept, ButtonPressesThroughTheSimulatedDeviceDecode) {
  const StudyManifest m = loadManifest(kIdent);
  for (int nexts : {0, 3}) {
    const ButtonRun b = pressButton(m.surfaces[1].scene, Cues{}, nexts);
    EXPECT_EQ(b.nexts, nexts);
    ASSERT_TRUE(b.confirm_s);
    EXPECT_GT(*b.confirm_s, 0.8);
  }
}
#endif

// Each scene rendered with every cue (the expectation) and without the pen's force.
struct Measured {
  std::vector<Percept> all, no_pen;
};
Measured measureAll(const std::vector<std::string>& scenes) {
  Measured m;
  for (const auto& s : scenes) {
    m.all.push_back(measureSurface(s, Cues{}));
    m.no_pen.push_back(measureSurface(s, Cues{true, true, false}));
    std::printf("%-28s", s.substr(s.rfind('/') + 1).c_str());
    for (const auto& f : m.all.back().features) std::printf(" %8.4f", f.value_or(-1));
    std::printf("\n");
  }
  return m;
}

// Accuracy of `trials` identifications under `cues`, every candidate presented in turn.
double accuracy(const Measured& m, const Cues& cues, std::uint64_t seed, int trials, double noise) {
  const std::vector<Percept>& expected = m.all;
  std::vector<Percept> presented;
  for (std::size_t i = 0; i < m.all.size(); ++i) presented.push_back(withoutSoundOrBall(cues.pen ? m.all[i] : m.no_pen[i], cues));
  const std::vector<std::string> scenes(m.all.size());
  SimulatedParticipant p(seed, noise);
  int correct = 0;
  for (int i = 0; i < trials; ++i) {
    const int truth = i % int(scenes.size());
    const IdentificationAnswer a = p.identify(presented[std::size_t(truth)], expected);
    correct += a.answer == truth;
    EXPECT_GE(a.ease, 1);
    EXPECT_LE(a.ease, 10);
    for (int k = 0; k < 3; ++k) {
      const bool on = k == 0 ? cues.sound : k == 1 ? cues.ball : cues.pen;
      EXPECT_EQ(a.use[std::size_t(k)].has_value(), on);
      if (on) {
        EXPECT_GE(*a.use[std::size_t(k)], 1);
        EXPECT_LE(*a.use[std::size_t(k)], 5);
        EXPECT_GE(*a.accuracy[std::size_t(k)], 1);
        EXPECT_LE(*a.accuracy[std::size_t(k)], 10);
      }
    }
  }
  return double(correct) / trials;
}

// Accuracy with every cue and with each removed, on the test manifest's surfaces `which`.
struct Accuracies {
  double all, no_sound, no_ball, no_pen;
};
Accuracies accuracies(const std::vector<int>& which, double noise, int n) {
  const StudyManifest m = loadManifest(kIdent);
  std::vector<std::string> scenes;
  for (int i : which) scenes.push_back(m.surfaces[std::size_t(i)].scene);
  const Measured measured = measureAll(scenes);
  const Accuracies a{accuracy(measured, Cues{}, 11, n, noise), accuracy(measured, Cues{false, true, true}, 11, n, noise),
                     accuracy(measured, Cues{true, false, true}, 11, n, noise),
                     accuracy(measured, Cues{true, true, false}, 11, n, noise)};
  std::printf("accuracy at %.0f JND, %d trials each: all %.3f, no sound %.3f, no ball %.3f, no pen %.3f\n", noise, n,
              a.all, a.no_sound, a.no_ball, a.no_pen);
  return a;
}

#ifdef THX_STUDY_MODEL_SLOW
// All five surfaces of the test manifest (docs/study.md §6.2's table; label slow).
TEST(ParticipantModelSlow, RemovingACueLowersAccuracy) {
  const Accuracies a = accuracies({0, 1, 2, 3, 4}, 2.0, 500);
  EXPECT_GT(a.all, a.no_sound);
  EXPECT_GT(a.all, a.no_ball);
  EXPECT_GT(a.all, a.no_pen);
  EXPECT_GT(a.no_pen, 1.0 / 5.0);  // still above chance on what is left
}
#else
// The short version: two surfaces (small bricks, steel grooves) that every cue tells apart.
TEST(ParticipantModel, RemovingACueLowersAccuracy) {
  const Accuracies a = accuracies({1, 3}, 4.0, 400);
  EXPECT_GT(a.all, a.no_sound);
  EXPECT_GT(a.all, a.no_ball);
  EXPECT_GT(a.all, a.no_pen);
  EXPECT_GT(a.no_pen, 0.5);  // still above chance on what is left
}

// Two candidates that differ only in their sound: without it, the answer is a coin toss.
TEST(ParticipantModel, ACueThatAloneSeparatesGoesToChance) {
  Percept a, b;
  for (int f = 0; f < kFeatureCount; ++f) a.features[std::size_t(f)] = b.features[std::size_t(f)] = 1.0;
  b.features[kSoundPitch] = 1.0 + 10 * kFeatureJnd[kSoundPitch];
  Percept a_mute = a;
  a_mute.features[kSoundPitch].reset();
  a_mute.features[kSoundRing].reset();
  SimulatedParticipant p(5);
  int with = 0, without = 0;
  for (int i = 0; i < 400; ++i) {
    with += p.identify(a, {a, b}).answer == 0;
    without += p.identify(a_mute, {a, b}).answer == 0;
  }
  EXPECT_EQ(with, 400);
  EXPECT_GT(without, 150);
  EXPECT_LT(without, 250);
}

TEST(ParticipantModel, SameSeedSameAnswersAndRatingsOnTheirScales) {
  Percept x, y;
  for (int f = 0; f < kFeatureCount; ++f) {
    x.features[std::size_t(f)] = 0.1 * f;
    y.features[std::size_t(f)] = 0.1 * f + kFeatureJnd[std::size_t(f)];
  }
  SimulatedParticipant p1(42), p2(42);
  for (int i = 0; i < 20; ++i) {
    const auto a1 = p1.identify(x, {x, y}), a2 = p2.identify(x, {x, y});
    EXPECT_EQ(a1.distances, a2.distances);
    const SurfaceRatings r1 = p1.rate(x, x, i % 2 ? Representation::Relief : Representation::Normal);
    const SurfaceRatings r2 = p2.rate(x, x, i % 2 ? Representation::Relief : Representation::Normal);
    EXPECT_EQ(r1.overall, r2.overall);
    for (int v : {r1.realism, r1.match_physics, r1.match_sound, r1.match_haptics, r1.overall}) {
      EXPECT_GE(v, 1);
      EXPECT_LE(v, 10);
    }
  }
}

#endif

}  // namespace
}  // namespace thx::study::test_participant_model
