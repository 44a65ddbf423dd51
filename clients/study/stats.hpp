#pragma once
// The statistics of the studies' analysis (docs/study.md §3): mean and SD, Student's (pooled),
// Welch's and the paired t-test with two-sided p values from Boost.Math's Student t distribution,
// Cohen's d with pooled SD, a confusion matrix. Checked against published datasets in
// tests/study/test_stats.cpp.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace thx::study {

struct Summary {
  std::size_t n = 0;
  double mean = 0;  // NaN when n == 0
  double sd = 0;    // sample SD (n - 1 in the denominator); NaN when n < 2
};
Summary summarize(std::span<const double> x);

struct TTest {
  double t = 0, df = 0, p = 0;  // p two-sided
  double mean_difference = 0;   // mean(a) - mean(b) (paired: mean of a[i] - b[i])
};

// Two-sided p of a t statistic with df degrees of freedom (df > 0, may be fractional; else
// std::logic_error: a caller's bug, the tests here derive df from at least two values).
double twoSidedP(double t, double df);

// Independent samples, equal variances assumed (pooled): df = na + nb - 2. nullopt when a
// sample has fewer than two values or both have zero spread (t undefined).
std::optional<TTest> studentT(std::span<const double> a, std::span<const double> b);
// Independent samples, unequal variances: df by Welch–Satterthwaite. nullopt as studentT.
std::optional<TTest> welchT(std::span<const double> a, std::span<const double> b);
// Paired samples a[i], b[i] (same size, else std::logic_error: a caller's bug): df = n - 1. nullopt for
// fewer than two pairs or differences without spread.
std::optional<TTest> pairedT(std::span<const double> a, std::span<const double> b);

// (mean(a) - mean(b)) / pooled SD, the pooled SD as in studentT. nullopt as studentT.
std::optional<double> cohensD(std::span<const double> a, std::span<const double> b);

// Counts of (truth, answer) pairs over fixed labels; rows are the truth.
class ConfusionMatrix {
 public:
  explicit ConfusionMatrix(std::vector<std::string> labels);
  // Throws std::logic_error for a label not in the list (a caller's bug: check labels first).
  void add(const std::string& truth, const std::string& answer);
  const std::vector<std::string>& labels() const { return labels_; }
  int count(std::size_t truth, std::size_t answer) const { return counts_[truth * labels_.size() + answer]; }
  int rowTotal(std::size_t truth) const;
  int total() const;
  int correct() const;  // the diagonal

 private:
  std::size_t index(const std::string& label) const;
  std::vector<std::string> labels_;
  std::vector<int> counts_;
};

}  // namespace thx::study
