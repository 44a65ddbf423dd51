#include "clients/study/stats.hpp"

#include <boost/math/distributions/students_t.hpp>

#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace thx::study {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TTest fromStatistic(double difference, double standard_error, double df) {
  const double t = difference / standard_error;
  return {t, df, twoSidedP(t, df), difference};
}

double pooledVariance(const Summary& a, const Summary& b) {
  const double na = double(a.n), nb = double(b.n);
  return ((na - 1) * a.sd * a.sd + (nb - 1) * b.sd * b.sd) / (na + nb - 2);
}

}  // namespace

Summary summarize(std::span<const double> x) {
  Summary s;
  s.n = x.size();
  if (x.empty()) return {0, kNaN, kNaN};
  s.mean = std::accumulate(x.begin(), x.end(), 0.0) / double(x.size());
  if (x.size() < 2) {
    s.sd = kNaN;
    return s;
  }
  // Two passes: the squared deviations from the mean, not sum(x²) - n·mean², which cancels
  // badly for times of a few seconds measured in long sessions.
  double ss = 0;
  for (double v : x) ss += (v - s.mean) * (v - s.mean);
  s.sd = std::sqrt(ss / double(x.size() - 1));
  return s;
}

double twoSidedP(double t, double df) {
  if (!(df > 0)) throw std::logic_error("twoSidedP: degrees of freedom must be > 0");
  if (std::isinf(t)) return 0.0;
  const boost::math::students_t dist(df);
  return 2.0 * boost::math::cdf(boost::math::complement(dist, std::fabs(t)));
}

std::optional<TTest> studentT(std::span<const double> a, std::span<const double> b) {
  const Summary sa = summarize(a), sb = summarize(b);
  if (sa.n < 2 || sb.n < 2) return std::nullopt;
  const double sp2 = pooledVariance(sa, sb);
  const double se = std::sqrt(sp2 * (1.0 / double(sa.n) + 1.0 / double(sb.n)));
  if (!(se > 0)) return std::nullopt;
  return fromStatistic(sa.mean - sb.mean, se, double(sa.n + sb.n - 2));
}

std::optional<TTest> welchT(std::span<const double> a, std::span<const double> b) {
  const Summary sa = summarize(a), sb = summarize(b);
  if (sa.n < 2 || sb.n < 2) return std::nullopt;
  const double va = sa.sd * sa.sd / double(sa.n), vb = sb.sd * sb.sd / double(sb.n);
  const double se = std::sqrt(va + vb);
  if (!(se > 0)) return std::nullopt;
  const double df = (va + vb) * (va + vb) / (va * va / double(sa.n - 1) + vb * vb / double(sb.n - 1));
  return fromStatistic(sa.mean - sb.mean, se, df);
}

std::optional<TTest> pairedT(std::span<const double> a, std::span<const double> b) {
  if (a.size() != b.size()) throw std::logic_error("pairedT: the two samples differ in size");
  std::vector<double> d(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) d[i] = a[i] - b[i];
  const Summary sd = summarize(d);
  if (sd.n < 2) return std::nullopt;
  const double se = sd.sd / std::sqrt(double(sd.n));
  if (!(se > 0)) return std::nullopt;
  return fromStatistic(sd.mean, se, double(sd.n - 1));
}

std::optional<double> cohensD(std::span<const double> a, std::span<const double> b) {
  const Summary sa = summarize(a), sb = summarize(b);
  if (sa.n < 2 || sb.n < 2) return std::nullopt;
  const double sp = std::sqrt(pooledVariance(sa, sb));
  if (!(sp > 0)) return std::nullopt;
  return (sa.mean - sb.mean) / sp;
}

ConfusionMatrix::ConfusionMatrix(std::vector<std::string> labels)
    : labels_(std::move(labels)), counts_(labels_.size() * labels_.size(), 0) {}

std::size_t ConfusionMatrix::index(const std::string& label) const {
  for (std::size_t i = 0; i < labels_.size(); ++i) {
    if (labels_[i] == label) return i;
  }
  // The session reader refuses a surface or answer outside the header's list (SessionError).
  throw std::logic_error("ConfusionMatrix: unknown label '" + label + "'");
}

void ConfusionMatrix::add(const std::string& truth, const std::string& answer) {
  ++counts_[index(truth) * labels_.size() + index(answer)];
}

int ConfusionMatrix::rowTotal(std::size_t truth) const {
  int n = 0;
  for (std::size_t j = 0; j < labels_.size(); ++j) n += count(truth, j);
  return n;
}

int ConfusionMatrix::total() const { return std::accumulate(counts_.begin(), counts_.end(), 0); }

int ConfusionMatrix::correct() const {
  int n = 0;
  for (std::size_t i = 0; i < labels_.size(); ++i) n += count(i, i);
  return n;
}

}  // namespace thx::study
