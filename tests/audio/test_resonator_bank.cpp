// The resonator bank against the closed form of a damped mode's impulse response.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "clients/audio/synthesis/resonator_bank.hpp"

namespace thx::audio::test_resonator_bank {
namespace {

constexpr double kRate = 44100.0;

// (g / omega_d) e^{-d t} sin(omega_d t)
double closedForm(double g, double f_hz, double d, double t) {
  const double wd = 2 * std::numbers::pi * f_hz;
  return g / wd * std::exp(-d * t) * std::sin(wd * t);
}

TEST(ResonatorBank, ImpulseResponseMatchesTheClosedFormForOneSecond) {
  // Low, middle and near-Nyquist modes, lightly and heavily damped.
  const std::vector<double> f{55.0, 440.0, 3000.0, 15000.0, 21000.0};
  const std::vector<double> d{0.5, 3.0, 40.0, 200.0, 5.0};
  for (std::size_t m = 0; m < f.size(); ++m) {
    ResonatorBank bank(kRate, 1);
    ASSERT_TRUE(bank.setModes({&f[m], 1}, {&d[m], 1}));
    const double g = 0.37;
    bank.strike({&g, 1});
    std::vector<double> y(static_cast<std::size_t>(kRate));
    bank.render(y);
    const double peak = g / (2 * std::numbers::pi * f[m]);
    double worst = 0;
    for (std::size_t n = 0; n < y.size(); ++n)
      worst = std::max(worst, std::fabs(y[n] - closedForm(g, f[m], d[m], double(n) / kRate)));
    EXPECT_LT(worst, 1e-6 * peak) << f[m] << " Hz";
  }
}

// The phase: the response starts at 0 and rises (a sine, not a cosine), its first peak where the
// closed form has it.
TEST(ResonatorBank, StartsAtZeroWithTheSinePhase) {
  const double f = 100.0, d = 0.0, g = 1.0;
  ResonatorBank bank(kRate, 1);
  ASSERT_TRUE(bank.setModes({&f, 1}, {&d, 1}));
  bank.strike({&g, 1});
  std::vector<double> y(441);
  bank.render(y);
  EXPECT_EQ(y[0], 0.0);
  EXPECT_GT(y[1], 0.0);
  const auto peak = std::max_element(y.begin(), y.end()) - y.begin();
  EXPECT_NEAR(double(peak), kRate / (4 * f), 1.0);  // a quarter period
}

// Decay: after T60 = ln(1000)/d the envelope is 1/1000 of its start.
TEST(ResonatorBank, EnvelopeFallsBySixtyDecibelsInT60) {
  const double f = 1000.0, d = 6.0, g = 1.0;
  ResonatorBank bank(kRate, 1);
  ASSERT_TRUE(bank.setModes({&f, 1}, {&d, 1}));
  bank.strike({&g, 1});
  const double t60 = std::log(1000.0) / d;
  std::vector<double> y(std::size_t(t60 * kRate) + 100);
  bank.render(y);
  auto envelope = [&](std::size_t at) {  // the largest |y| over one period from `at`
    double e = 0;
    for (std::size_t n = at; n < at + std::size_t(kRate / f); ++n) e = std::max(e, std::fabs(y[n]));
    return e;
  };
  const double start = envelope(0), end = envelope(std::size_t(t60 * kRate) - std::size_t(kRate / f) / 2);
  EXPECT_NEAR(end / start, 1e-3, 0.02e-3);
}

TEST(ResonatorBank, ManyModesSumAndBlockSizeDoesNotMatter) {
  const std::vector<double> f{200.0, 310.0, 777.0, 5000.0}, d{1.0, 2.0, 3.0, 30.0}, g{1.0, -0.5, 0.25, 2.0};
  ResonatorBank one(kRate, 8), blocks(kRate, 8);
  ASSERT_TRUE(one.setModes(f, d));
  ASSERT_TRUE(blocks.setModes(f, d));
  one.strike(g);
  blocks.strike(g);
  std::vector<double> whole(4096), parts(4096);
  one.render(whole);
  for (std::size_t at = 0; at < parts.size(); at += 100)
    blocks.render(std::span<double>(parts).subspan(at, std::min<std::size_t>(100, parts.size() - at)));
  for (std::size_t n = 0; n < whole.size(); ++n) {
    double sum = 0;
    for (std::size_t k = 0; k < f.size(); ++k) sum += closedForm(g[k], f[k], d[k], double(n) / kRate);
    ASSERT_NEAR(whole[n], sum, 1e-9) << n;
    ASSERT_EQ(whole[n], parts[n]) << n;
  }
}

// Under a budget of 2 the bank sounds exactly like a bank of its first two modes, and computes
// no more; a struck mode outside the budget waits and sounds once admitted.
TEST(ResonatorBank, BudgetRendersOnlyTheFirstModes) {
  const std::vector<double> f{200.0, 310.0, 777.0, 5000.0}, d{1.0, 2.0, 3.0, 30.0}, g{1.0, -0.5, 0.25, 2.0};
  ResonatorBank limited(kRate, 4), two(kRate, 2);
  ASSERT_TRUE(limited.setModes(f, d));
  ASSERT_TRUE(two.setModes(std::span(f).first(2), std::span(d).first(2)));
  limited.setBudget(2);
  limited.strike(g);
  two.strike(std::span(g).first(2));
  std::vector<double> a(1000), b(1000);
  for (int block = 0; block < 3; ++block) {
    limited.render(a);
    two.render(b);
    EXPECT_EQ(a, b) << "block " << block;
    EXPECT_EQ(limited.lastRenderedModes(), 2u);
  }
  limited.setBudget(4);
  limited.render(a);
  EXPECT_EQ(limited.lastRenderedModes(), 4u);
  two.render(b);
  double difference = 0;
  for (std::size_t n = 0; n < a.size(); ++n) difference = std::max(difference, std::fabs(a[n] - b[n]));
  EXPECT_GT(difference, 1e-6);  // modes 3 and 4 now sound
}

TEST(ResonatorBank, RefusesModesItCannotRepresent) {
  ResonatorBank bank(kRate, 2);
  const std::vector<double> ok{100.0, 200.0}, d{1.0, 1.0};
  EXPECT_TRUE(bank.setModes(ok, d));
  const std::vector<double> three{1.0, 2.0, 3.0}, d3{1.0, 1.0, 1.0};
  EXPECT_FALSE(bank.setModes(three, d3));  // above capacity
  const std::vector<double> nyquist{100.0, 22050.0};
  EXPECT_FALSE(bank.setModes(nyquist, d));
  const std::vector<double> negative_decay{-1.0, 1.0};
  EXPECT_FALSE(bank.setModes(ok, negative_decay));
  EXPECT_EQ(bank.size(), 2u);  // unchanged
}

}  // namespace
}  // namespace thx::audio::test_resonator_bank
