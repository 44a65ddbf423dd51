// The statistics library against datasets with published results. Each dataset names its source;
// docs/study.md §3 lists the same sources. Tolerances are half a unit in the last published digit.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "clients/study/stats.hpp"

namespace thx::study::test_stats {
namespace {

// Student (1908), "The probable error of a mean", Biometrika 6(1), p. 20: additional hours of
// sleep of ten patients under two soporifics (Cushny & Peebles 1905); R's datasets::sleep.
// Published (R's ?sleep and ?t.test examples, paired = TRUE): t = -4.0621, df = 9,
// p-value = 0.002833; as independent groups: Welch t = -1.8608, df = 17.776, p = 0.07939;
// var.equal = TRUE: t = -1.8608, df = 18, p = 0.07919.
const std::vector<double> kSleep1{0.7, -1.6, -0.2, -1.2, -0.1, 3.4, 3.7, 0.8, 0.0, 2.0};
const std::vector<double> kSleep2{1.9, 0.8, 1.1, 0.1, -0.1, 4.4, 5.5, 1.6, 4.6, 3.4};

// Wikipedia, "Welch's t-test", section Examples, example 2: two samples of unequal size
// and variance. Published: Welch t = -1.57, df = 9.9, p = 0.149; Student t = -2.10, df = 28,
// p = 0.045.
const std::vector<double> kWelchA{17.2, 20.9, 22.6, 18.1, 21.7, 21.4, 23.5, 24.2, 14.7, 21.8};
const std::vector<double> kWelchB{21.5, 22.8, 21.0, 23.0, 21.6, 23.6, 22.5, 20.7, 23.4, 21.8,
                                  20.7, 21.7, 21.5, 22.5, 23.6, 21.5, 22.5, 23.5, 21.5, 21.8};

TEST(Stats, SummaryOfATextbookSample) {
  // Mean 5, squared deviations summing to 32: sample SD sqrt(32 / 7).
  const std::vector<double> x{2, 4, 4, 4, 5, 5, 7, 9};
  const Summary s = summarize(x);
  EXPECT_EQ(s.n, 8u);
  EXPECT_DOUBLE_EQ(s.mean, 5.0);
  EXPECT_DOUBLE_EQ(s.sd, std::sqrt(32.0 / 7.0));
  EXPECT_TRUE(std::isnan(summarize(std::vector<double>{3.0}).sd));
  EXPECT_TRUE(std::isnan(summarize(std::vector<double>{}).mean));
}

TEST(Stats, PairedTOnStudentsSleepData) {
  const auto r = pairedT(kSleep1, kSleep2);
  ASSERT_TRUE(r);
  EXPECT_NEAR(r->t, -4.0621, 5e-5);
  EXPECT_DOUBLE_EQ(r->df, 9.0);
  EXPECT_NEAR(r->p, 0.002833, 5e-7);
  EXPECT_NEAR(r->mean_difference, -1.58, 1e-12);
}

TEST(Stats, WelchAndStudentOnStudentsSleepData) {
  const auto w = welchT(kSleep1, kSleep2);
  ASSERT_TRUE(w);
  EXPECT_NEAR(w->t, -1.8608, 5e-5);
  EXPECT_NEAR(w->df, 17.776, 5e-4);
  EXPECT_NEAR(w->p, 0.07939, 5e-6);
  const auto s = studentT(kSleep1, kSleep2);
  ASSERT_TRUE(s);
  EXPECT_NEAR(s->t, -1.8608, 5e-5);  // equal sizes: the pooled and the Welch statistic coincide
  EXPECT_DOUBLE_EQ(s->df, 18.0);
  EXPECT_NEAR(s->p, 0.07919, 5e-6);
}

TEST(Stats, WelchAndStudentOnUnequalSamples) {
  const auto w = welchT(kWelchA, kWelchB);
  ASSERT_TRUE(w);
  EXPECT_NEAR(w->t, -1.57, 5e-3);
  EXPECT_NEAR(w->df, 9.9, 5e-2);
  EXPECT_NEAR(w->p, 0.149, 5e-4);
  const auto s = studentT(kWelchA, kWelchB);
  ASSERT_TRUE(s);
  EXPECT_NEAR(s->t, -2.10, 5e-3);
  EXPECT_DOUBLE_EQ(s->df, 28.0);
  EXPECT_NEAR(s->p, 0.045, 5e-4);
}

TEST(Stats, TwoSidedPAgreesWithTablesAndTheCauchyCase) {
  // t(0.975, 9) = 2.262157 (any two-sided t table, e.g. NIST/SEMATECH e-Handbook of Statistical Methods §1.3.6.7.2).
  EXPECT_NEAR(twoSidedP(2.262157, 9), 0.05, 1e-6);
  EXPECT_NEAR(twoSidedP(-2.262157, 9), 0.05, 1e-6);
  // df = 1 is the Cauchy distribution: P(|T| > t) = 1 - 2 atan(t) / pi.
  for (double t : {0.3, 1.0, 4.0}) {
    EXPECT_NEAR(twoSidedP(t, 1), 1.0 - 2.0 * std::atan(t) / std::numbers::pi, 1e-12) << t;
  }
  EXPECT_DOUBLE_EQ(twoSidedP(0.0, 5), 1.0);
  EXPECT_THROW(twoSidedP(1.0, 0.0), std::logic_error);
}

TEST(Stats, CohensDWithPooledSd) {
  // Means 2 and 5, both SDs 1: d = -3 exactly.
  const auto d = cohensD(std::vector<double>{1, 2, 3}, std::vector<double>{4, 5, 6});
  ASSERT_TRUE(d);
  EXPECT_DOUBLE_EQ(*d, -3.0);
  // With the pooled SD, d = t_Student * sqrt(1/na + 1/nb) for any two samples.
  const auto s = studentT(kWelchA, kWelchB);
  const auto dw = cohensD(kWelchA, kWelchB);
  ASSERT_TRUE(s && dw);
  EXPECT_NEAR(*dw, s->t * std::sqrt(1.0 / 10 + 1.0 / 20), 1e-12);
}

TEST(Stats, UndefinedTestsAreEmpty) {
  const std::vector<double> one{1.0}, two{1.0, 2.0}, flat{3.0, 3.0, 3.0};
  EXPECT_FALSE(studentT(one, two));
  EXPECT_FALSE(welchT(two, one));
  EXPECT_FALSE(studentT(flat, flat));
  EXPECT_FALSE(welchT(flat, flat));
  EXPECT_FALSE(pairedT(flat, flat));
  EXPECT_FALSE(cohensD(flat, flat));
  EXPECT_FALSE(pairedT(one, one));
  EXPECT_THROW(pairedT(one, two), std::logic_error);
}

TEST(Stats, ConfusionMatrixCounts) {
  ConfusionMatrix m({"wood", "metal", "bricks"});
  m.add("wood", "wood");
  m.add("wood", "metal");
  m.add("metal", "metal");
  m.add("bricks", "wood");
  EXPECT_EQ(m.count(0, 0), 1);
  EXPECT_EQ(m.count(0, 1), 1);
  EXPECT_EQ(m.count(2, 0), 1);
  EXPECT_EQ(m.count(1, 0), 0);
  EXPECT_EQ(m.rowTotal(0), 2);
  EXPECT_EQ(m.total(), 4);
  EXPECT_EQ(m.correct(), 2);
  EXPECT_THROW(m.add("glass", "wood"), std::logic_error);
}

}  // namespace
}  // namespace thx::study::test_stats
