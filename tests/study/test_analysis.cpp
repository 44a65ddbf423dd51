// Study 1 and Study 2 analysis on the hand-made sessions of study_fixtures.hpp; every expected
// number is worked out from the fixture in the comments.
#include <gtest/gtest.h>

#include <cmath>

#include "clients/study/analysis.hpp"
#include "clients/study/report.hpp"
#include "tests/study/study_fixtures.hpp"
#include "tests/support/error_text.hpp"

namespace thx::study::test_analysis {
namespace {

using test::errorOf;

TEST(StudyAnalysis, IdentificationByConditionCueAndSurface) {
  const IdentificationResults r = analyzeIdentification(fixtures::identificationSessions());
  EXPECT_EQ(r.sessions, 2);
  // All cues: P1 right on trials 1, 2 (10 s, 20 s), wrong on 3; P2 right on 1, 2 (14, 16), wrong
  // on 3: 4 of 6, times mean 15, squared deviations 25 + 25 + 1 + 1 = 52 over 3.
  ASSERT_EQ(r.by_condition.size(), 2u);
  EXPECT_EQ(r.by_condition[0].label, "all cues");
  EXPECT_EQ(r.by_condition[0].trials, 6);
  EXPECT_EQ(r.by_condition[0].correct, 4);
  EXPECT_DOUBLE_EQ(r.by_condition[0].idRate(), 4.0 / 6.0);
  EXPECT_DOUBLE_EQ(r.by_condition[0].time().mean, 15.0);
  EXPECT_DOUBLE_EQ(r.by_condition[0].time().sd, std::sqrt(52.0 / 3.0));
  // One cue removed: right on P1's 5, 6 (12, 18) and P2's 4, 6 (30, 22).
  EXPECT_EQ(r.by_condition[1].label, "one cue removed");
  EXPECT_EQ(r.by_condition[1].correct, 4);
  EXPECT_DOUBLE_EQ(r.by_condition[1].time().mean, 20.5);

  ASSERT_EQ(r.by_cue.size(), 4u);
  const char* labels[] = {"all cues", "no sound", "no ball", "no pen"};
  const int correct[] = {4, 1, 1, 2};
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(r.by_cue[std::size_t(i)].label, labels[i]);
    EXPECT_EQ(r.by_cue[std::size_t(i)].correct, correct[i]) << labels[i];
  }
  EXPECT_EQ(r.by_cue[3].correct_times_s, (std::vector<double>{18, 22}));
  // No pen (18, 22) against all cues (10, 20, 14, 16); one correct time is too few for a test.
  const TimeComparison& pen = r.by_cue_against_all[3];
  ASSERT_TRUE(pen.welch && pen.student && pen.d);
  EXPECT_DOUBLE_EQ(pen.welch->mean_difference, 5.0);
  EXPECT_EQ(pen.welch->t, welchT(std::vector<double>{18, 22}, std::vector<double>{10, 20, 14, 16})->t);
  EXPECT_DOUBLE_EQ(pen.student->df, 4.0);
  EXPECT_FALSE(r.by_cue_against_all[1].welch);
  EXPECT_FALSE(r.by_cue_against_all[0].welch);

  // metal_a was drawn twice (P1 trial 3, P2 trial 5) and never named.
  ASSERT_EQ(r.by_surface.size(), 6u);
  EXPECT_EQ(r.by_surface[2].label, "metal_a");
  EXPECT_EQ(r.by_surface[2].family, "metal");
  EXPECT_EQ(r.by_surface[2].trials, 2);
  EXPECT_EQ(r.by_surface[2].correct, 0);
  EXPECT_TRUE(std::isnan(r.by_surface[2].time().mean));

  // Confusions: bricks_b→wood_a, metal_a→metal_b, metal_a→bricks_a, wood_b→wood_a.
  EXPECT_EQ(r.surfaces.total(), 12);
  EXPECT_EQ(r.surfaces.correct(), 8);
  EXPECT_EQ(r.surfaces.count(2, 3), 1);
  EXPECT_EQ(r.surfaces.count(2, 0), 1);
  EXPECT_EQ(r.surfaces.count(1, 4), 1);
  // By family, metal_a→metal_b and wood_b→wood_a are right: 10 of 12.
  EXPECT_EQ(r.families.labels(), (std::vector<std::string>{"bricks", "metal", "wood"}));
  EXPECT_EQ(r.families.correct(), 10);
  EXPECT_EQ(r.families.count(0, 2), 1);
  EXPECT_EQ(r.families.count(1, 0), 1);
}

TEST(StudyAnalysis, RatingsPairedWithinParticipants) {
  const RatingResults r = analyzeRatings(fixtures::ratingSessions());
  EXPECT_EQ(r.sessions, 4);
  EXPECT_EQ(r.unpaired_participants, (std::vector<std::string>{"P4"}));
  ASSERT_EQ(r.paired.size(), 5u);
  EXPECT_EQ(r.paired[0].rating, Rating::Realism);
  // Realism is 8 for relief and 6 for normal for everyone: differences without spread, no test.
  EXPECT_FALSE(r.paired[0].paired);
  EXPECT_FALSE(r.paired[0].d);
  // Overall: relief means P1 (8+6)/2 = 7, P2 (9+7)/2 = 8, P3 (6+6)/2 = 6; normal 5, 5, 4.
  // Differences 2, 3, 2: mean 7/3, SD sqrt(1/3), t = (7/3) / (sqrt(1/3) / sqrt(3)) = 7, df 2,
  // and for df = 2 the two-sided p is 1 - t / sqrt(2 + t²).
  const RatingComparison& overall = r.paired[4];
  EXPECT_EQ(overall.rating, Rating::Overall);
  EXPECT_EQ(overall.relief, (std::vector<double>{7, 8, 6}));
  EXPECT_EQ(overall.normal, (std::vector<double>{5, 5, 4}));
  ASSERT_TRUE(overall.paired);
  EXPECT_NEAR(overall.paired->t, 7.0, 1e-12);
  EXPECT_DOUBLE_EQ(overall.paired->df, 2.0);
  EXPECT_NEAR(overall.paired->p, 1.0 - 7.0 / std::sqrt(51.0), 1e-12);
  // d: relief SD 1, normal SD sqrt(1/3), pooled sqrt(2/3); (7 - 14/3) / sqrt(2/3).
  ASSERT_TRUE(overall.d);
  EXPECT_NEAR(*overall.d, (7.0 / 3.0) / std::sqrt(2.0 / 3.0), 1e-12);

  // Per surface: wood_1 overall, relief by P1 (8) and P3 (6), normal by P2 (6) and P4 (5).
  const auto it = std::find_if(r.by_surface.begin(), r.by_surface.end(), [](const SurfaceRating& s) {
    return s.surface == "wood_1" && s.rating == Rating::Overall;
  });
  ASSERT_NE(it, r.by_surface.end());
  EXPECT_EQ(it->relief, (std::vector<double>{8, 6}));
  EXPECT_EQ(it->normal, (std::vector<double>{6, 5}));
  ASSERT_TRUE(it->welch);
  EXPECT_DOUBLE_EQ(it->welch->mean_difference, 1.5);
  EXPECT_EQ(r.by_surface.size(), 4u * 5u);
}

TEST(StudyAnalysis, EachStudyIgnoresTheOther) {
  std::vector<Session> all = fixtures::identificationSessions();
  for (Session& s : fixtures::ratingSessions()) all.push_back(s);
  EXPECT_EQ(analyzeIdentification(all).sessions, 2);
  EXPECT_EQ(analyzeRatings(all).sessions, 4);
  EXPECT_EQ(analyzeIdentification(fixtures::ratingSessions()).sessions, 0);
}

TEST(StudyAnalysis, InconsistentSessionsAreRefused) {
  std::vector<Session> twice = fixtures::identificationSessions();
  twice[1].header.participant = "P1";
  EXPECT_EQ(errorOf([&] { analyzeIdentification(twice); }),
            "p2_id.csv: participant 'P1' already has a session of study identification in p1_id.csv");
  std::vector<Session> other = fixtures::identificationSessions();
  other[1].header.surfaces[0].family = "stone";
  EXPECT_EQ(errorOf([&] { analyzeIdentification(other); }),
            "p2_id.csv: header 'surfaces' differs from p1_id.csv's (every identification session offers the same "
            "surfaces and families)");
  std::vector<Session> mesh = fixtures::ratingSessions();
  mesh[2].trials[1].representation = Representation::Mesh;
  EXPECT_EQ(errorOf([&] { analyzeRatings(mesh); }),
            "p3_rv.csv: trial 2: representation mesh: the relief-vs-normal analysis compares relief and normal "
            "maps only");
}

TEST(StudyAnalysis, TablesCarryTheNumbers) {
  const std::vector<Table> id = identificationTables(analyzeIdentification(fixtures::identificationSessions()));
  ASSERT_EQ(id.size(), 6u);
  EXPECT_EQ(id[0].name, "identification_by_condition");
  EXPECT_EQ(id[0].rows[0], (std::vector<std::string>{"all cues", "6", "4", "0.667", "15.00", "4.16"}));
  const std::string md = markdown(id[1]);
  EXPECT_NE(md.find("| no sound | 2 | 1 | 0.500 | 30.00 | – | – |"), std::string::npos) << md;
  // Ease is 5 + trial % 3: trials 1, 2, 3 with all cues give 6, 7, 5 for both participants;
  // sound is not rated without sound; no pen (trial 6) gives ease 5.
  EXPECT_EQ(id[2].name, "identification_ratings");
  EXPECT_EQ(id[2].rows[0][1], "6.00");
  EXPECT_EQ(id[2].rows[0][2], "0.89");  // 6, 7, 5, 6, 7, 5: squared deviations 4 over 5
  EXPECT_EQ(id[2].rows[1][3], "");      // no sound: use_sound never given
  EXPECT_EQ(id[2].rows[3][1], "5.00");
  const std::string confusion = csv(id[4]);
  EXPECT_EQ(confusion.substr(0, confusion.find('\n')),
            "truth \\ answer,bricks_a,bricks_b,metal_a,metal_b,wood_a,wood_b,trials,id_rate");
  EXPECT_NE(confusion.find("\nmetal_a,1,0,0,1,0,0,2,0.000\n"), std::string::npos) << confusion;

  const std::vector<Table> rt = ratingTables(analyzeRatings(fixtures::ratingSessions()));
  ASSERT_EQ(rt.size(), 2u);
  EXPECT_EQ(rt[0].rows[4], (std::vector<std::string>{"overall", "3", "7.00", "1.00", "4.67", "0.58", "7.000", "2.00",
                                                     "0.0198", "2.858"}));
  EXPECT_EQ(rt[0].rows[0][6], "");  // realism: no test
  EXPECT_NE(rt[0].note.find("left out (rated one representation only): P4."), std::string::npos);
}

}  // namespace
}  // namespace thx::study::test_analysis
