// Trial plans (docs/study.md §5.2): deterministic from the seed, Study 1's cue schedule, Study 2's
// split into relief and normal maps.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "clients/study/trial_plan.hpp"

namespace thx::study::test_trial_plan {
namespace {

StudyManifest manifest(Study study, int n) {
  StudyManifest m;
  m.study = study;
  for (int i = 0; i < n; ++i) {
    const std::string k = std::to_string(i);
    m.surfaces.push_back({"s" + k, "f", "scene" + k + ".yaml", "relief" + k + ".yaml", "normal" + k + ".yaml"});
  }
  return m;
}

bool samePlan(const std::vector<PlannedTrial>& a, const std::vector<PlannedTrial>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].surface != b[i].surface || a[i].scene != b[i].scene || !(a[i].cues == b[i].cues) ||
        a[i].first_look != b[i].first_look || a[i].representation != b[i].representation)
      return false;
  return true;
}

TEST(StudyRng, KnownSequenceAndBounds) {
  // SplitMix64's published first output for seed 0 (Vigna's reference implementation).
  StudyRng r(0);
  EXPECT_EQ(r.next(), 0xe220a8397b1dcdafULL);
  StudyRng b(9);
  std::vector<int> counts(7, 0);
  for (int i = 0; i < 7000; ++i) ++counts[std::size_t(b.below(7))];
  for (int c : counts) EXPECT_GT(c, 800);  // each value about 1000 times
  EXPECT_EQ(b.below(1), 0);
}

TEST(TrialPlan, IdentificationCueSchedule) {
  const StudyManifest m = manifest(Study::Identification, 10);
  std::set<std::vector<int>> orders;
  std::set<int> drawn;
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    const auto plan = planIdentification(m, seed);
    ASSERT_EQ(plan.size(), 6u);
    std::vector<int> removed;
    for (std::size_t i = 0; i < 6; ++i) {
      const PlannedTrial& t = plan[i];
      EXPECT_EQ(t.trial, int(i) + 1);
      ASSERT_GE(t.surface, 0);
      ASSERT_LT(t.surface, 10);
      EXPECT_EQ(t.scene, m.surfaces[std::size_t(t.surface)].scene);
      EXPECT_GE(t.first_look, 0);
      EXPECT_LT(t.first_look, 10);
      drawn.insert(t.surface);
      const int off = int(!t.cues.sound) + int(!t.cues.ball) + int(!t.cues.pen);
      if (i < 3) {
        EXPECT_EQ(off, 0) << "trial " << t.trial;
      } else {
        ASSERT_EQ(off, 1) << "trial " << t.trial;
        removed.push_back(!t.cues.sound ? 0 : !t.cues.ball ? 1 : 2);
      }
    }
    std::vector<int> sorted = removed;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(sorted, (std::vector<int>{0, 1, 2})) << "seed " << seed;
    orders.insert(removed);
    EXPECT_TRUE(samePlan(plan, planIdentification(m, seed)));
  }
  EXPECT_EQ(orders.size(), 6u);   // every order of the three removals occurs
  EXPECT_EQ(drawn.size(), 10u);   // every surface is drawn by some seed
  EXPECT_FALSE(samePlan(planIdentification(m, 1), planIdentification(m, 2)));
}

TEST(TrialPlan, ReliefVsNormalSplit) {
  const StudyManifest m = manifest(Study::ReliefVsNormal, 6);
  std::map<int, int> relief_count;
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    const auto plan = planReliefVsNormal(m, seed);
    ASSERT_EQ(plan.size(), 6u);
    std::set<int> seen;
    int relief = 0;
    for (const PlannedTrial& t : plan) {
      EXPECT_TRUE(seen.insert(t.surface).second) << "a surface twice, seed " << seed;
      EXPECT_EQ(t.cues, Cues{});
      const auto& s = m.surfaces[std::size_t(t.surface)];
      if (t.representation == Representation::Relief) {
        ++relief;
        ++relief_count[t.surface];
        EXPECT_EQ(t.scene, s.relief);
      } else {
        EXPECT_EQ(t.representation, Representation::Normal);
        EXPECT_EQ(t.scene, s.normal);
      }
    }
    EXPECT_EQ(relief, 3);
    EXPECT_TRUE(samePlan(plan, planReliefVsNormal(m, seed)));
  }
  for (int i = 0; i < 6; ++i) EXPECT_GT(relief_count[i], 60) << "surface " << i;  // about 100 of 200
  EXPECT_TRUE(samePlan(planSession(m, 4), planReliefVsNormal(m, 4)));
}

}  // namespace
}  // namespace thx::study::test_trial_plan
