// The Hertz contact time and the half-sine pulse's effect on each mode (contact_pulse.hpp,
// docs/audio.md §9): against the numerically integrated Hertz impact and the resonator's own
// response to the sampled force.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "base/error.hpp"
#include "clients/audio/synthesis/contact_pulse.hpp"
#include "clients/audio/synthesis/resonator_bank.hpp"
#include "scenes/materials.hpp"

namespace test_contact_pulse {

namespace {

using namespace thx::audio;

HertzSide sphereOf(const char* material, double radius, double mass) {
  const auto m = *thx::scene::findMaterial(material);
  return {m.youngs_modulus_pa, m.poisson_ratio, radius, mass};
}
HertzSide groundOf(const char* material) {
  const auto m = *thx::scene::findMaterial(material);
  return {m.youngs_modulus_pa, m.poisson_ratio};
}

// m x'' = -k x^(3/2), k = 4/3 E* sqrt(R*), from x = 0 at speed v until x returns to 0 (RK4).
double integratedHertzDuration(const HertzSide& a, const HertzSide& b, double v) {
  const double e = 1.0 / ((1 - a.poisson * a.poisson) / a.youngs_pa + (1 - b.poisson * b.poisson) / b.youngs_pa);
  const double r = 1.0 / (1.0 / a.radius_m + (std::isfinite(b.radius_m) ? 1.0 / b.radius_m : 0.0));
  const double m = 1.0 / (1.0 / a.mass_kg + (std::isfinite(b.mass_kg) ? 1.0 / b.mass_kg : 0.0));
  const double k = 4.0 / 3.0 * e * std::sqrt(r);
  auto acc = [&](double x) { return x > 0 ? -k / m * std::pow(x, 1.5) : 0.0; };
  const double guess = hertzContactDuration(a, b, v), h = guess * 1e-5;
  double x = 0, u = v, t = 0;
  while (true) {
    const double k1x = u, k1u = acc(x);
    const double k2x = u + 0.5 * h * k1u, k2u = acc(x + 0.5 * h * k1x);
    const double k3x = u + 0.5 * h * k2u, k3u = acc(x + 0.5 * h * k2x);
    const double k4x = u + h * k3u, k4u = acc(x + h * k3x);
    const double nx = x + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    const double nu = u + h / 6 * (k1u + 2 * k2u + 2 * k3u + k4u);
    if (t > 0 && nx <= 0) return t + h * x / (x - nx);  // crossing, interpolated
    x = nx, u = nu, t += h;
  }
}

TEST(ContactPulse, HertzDurationMatchesTheIntegratedImpact) {
  const HertzSide marble = sphereOf("glass", 0.006, 0.00235), ball = sphereOf("steel", 0.006, 0.0071);
  for (double v : {0.05, 0.5, 3.0}) {
    for (const auto& [a, b] : {std::pair{marble, groundOf("brick")}, std::pair{ball, groundOf("steel")}, std::pair{marble, ball}}) {
      const double tau = hertzContactDuration(a, b, v), ref = integratedHertzDuration(a, b, v);
      std::printf("[measured] v %.2f m/s: tau %.2f us (integrated %.2f us)\n", v, tau * 1e6, ref * 1e6);
      EXPECT_NEAR(tau / ref, 1.0, 2e-3) << "v " << v;
    }
  }
}

TEST(ContactPulse, ShorterForFasterAndHarderContacts) {
  const HertzSide marble = sphereOf("glass", 0.006, 0.00235);
  const HertzSide brick = groundOf("brick");
  // v^(-1/5): 32 times faster, half as long.
  EXPECT_NEAR(hertzContactDuration(marble, brick, 0.01) / hertzContactDuration(marble, brick, 0.32), 2.0, 1e-12);
  // E*^(-2/5): both moduli x 32 -> E* x 32 -> tau / 32^(2/5) = tau / 4.
  HertzSide hard_marble = marble, hard_brick = brick;
  hard_marble.youngs_pa *= 32, hard_brick.youngs_pa *= 32;
  EXPECT_NEAR(hertzContactDuration(marble, brick, 0.3) / hertzContactDuration(hard_marble, hard_brick, 0.3), 4.0, 1e-12);
  // A steel surface is harder than brick: shorter.
  EXPECT_LT(hertzContactDuration(marble, groundOf("steel"), 0.3), hertzContactDuration(marble, brick, 0.3));
  // No elastic, curved, massive side: no Hertz contact.
  EXPECT_THROW(hertzContactDuration(HertzSide{}, groundOf("steel"), 0.3), thx::Error);
  EXPECT_THROW(hertzContactDuration(marble, brick, 0.0), thx::Error);
}

// The resonator driven by the sampled half-sine force against one strike of J P(w tau) at the
// pulse's centre: the same ringing after the pulse, for slow, comparable and fast modes.
TEST(ContactPulse, ModeRingsAsIfStruckByThePulsesSpectrumAtItsCentre) {
  constexpr double fs = 4.0e6, tau = 2.0e-4, J = 1.0, pi = std::numbers::pi;
  const auto pulse_samples = std::size_t(std::llround(tau * fs));
  for (double f : {20.0, 500.0, 2500.0, 5000.0, 9000.0}) {
    const double w = 2 * pi * f, P = halfSinePulseFactor(w, tau);
    const double freq[1] = {f}, decay[1] = {2.0};
    ResonatorBank force(fs, 1), strike(fs, 1);
    force.setModes(freq, decay);
    strike.setModes(freq, decay);
    const std::size_t n = pulse_samples + std::size_t(fs * 2.0 / f);  // the pulse and two periods
    std::vector<double> a(n), b(n);
    for (std::size_t k = 0; k < n; ++k) {
      if (k <= pulse_samples) {  // g = F(t_k) dt at every sample of the pulse (F = 0 at both ends)
        const double t = double(k) / fs;
        const double g[1] = {pi * J / (2 * tau) * std::sin(pi * t / tau) / fs};
        force.strike(g);
      }
      force.render(std::span<double>(a).subspan(k, 1));
      if (k == pulse_samples / 2) {
        const double g[1] = {J * P};
        strike.strike(g);
      }
      strike.render(std::span<double>(b).subspan(k, 1));
    }
    double peak = 0, err = 0;
    for (std::size_t k = pulse_samples + 1; k < n; ++k) peak = std::max(peak, std::fabs(a[k])), err = std::max(err, std::fabs(a[k] - b[k]));
    std::printf("[measured] f %.0f Hz, w tau = %.3f: P = %+.4f, ringing error %.2e of its peak\n", f, w * tau, P, err / peak);
    EXPECT_LT(err, 2e-3 * peak) << f << " Hz";
  }
  EXPECT_NEAR(halfSinePulseFactor(1e-3, tau), 1.0, 1e-12);  // a period >> the pulse: the whole impulse
  EXPECT_NEAR(halfSinePulseFactor(pi / tau, tau), pi / 4, 1e-9);
  EXPECT_NEAR(halfSinePulseFactor(3 * pi / tau, tau), 0.0, 1e-12);
  EXPECT_LT(halfSinePulseFactor(4 * pi / tau, tau), 0.0);
}

}  // namespace

}  // namespace test_contact_pulse
