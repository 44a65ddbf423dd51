#include "clients/audio/synthesis/contact_pulse.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "base/error.hpp"

namespace thx::audio {

double hertzContactDuration(const HertzSide& a, const HertzSide& b, double v) {
  if (!(v > 0.0) || !std::isfinite(v))
    throw Error(Error::Kind::Config, "Hertz contact: approach speed must be > 0, got " + std::to_string(v));
  auto compliance = [](const HertzSide& s) { return std::isfinite(s.youngs_pa) ? (1.0 - s.poisson * s.poisson) / s.youngs_pa : 0.0; };
  auto inverse = [](double x) { return std::isfinite(x) ? 1.0 / x : 0.0; };
  const double c = compliance(a) + compliance(b);
  const double curvature = inverse(a.radius_m) + inverse(b.radius_m);
  const double inv_mass = inverse(a.mass_kg) + inverse(b.mass_kg);
  if (!(c > 0.0) || !(curvature > 0.0) || !(inv_mass > 0.0))
    throw Error(Error::Kind::Config, "Hertz contact needs a finite modulus, radius and mass on some side");
  const double e_star = 1.0 / c, r_star = 1.0 / curvature, m_star = 1.0 / inv_mass;
  return 2.868 * std::pow(m_star * m_star / (r_star * e_star * e_star * v), 0.2);
}

double halfSinePulseFactor(double omega, double tau) {
  constexpr double pi = std::numbers::pi, pi2 = pi * pi;
  const double x = std::fabs(omega * tau);
  const double d = pi2 - x * x;
  if (std::fabs(x - pi) < 1e-6) return pi / 4.0;  // the removable singularity
  return pi2 * std::cos(0.5 * x) / d;
}

}  // namespace thx::audio
