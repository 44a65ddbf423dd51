#include "clients/audio/analysis/elastic_material.hpp"

#include <cmath>

#include "base/number_text.hpp"
#include "clients/audio/analysis/modal_error.hpp"

namespace thx::audio {

void checkMaterial(const std::string& object, const ElasticMaterial& m) {
  auto fail = [&](const char* field, double v, const char* expected) {
    throw ModalError(object + ": material '" + m.name + "': " + field + " " + numberText(v) + ": expected " +
                     expected);
  };
  if (!(std::isfinite(m.density_kg_per_m3) && m.density_kg_per_m3 > 0)) fail("density", m.density_kg_per_m3, "> 0 kg/m^3");
  if (!(std::isfinite(m.youngs_modulus_pa) && m.youngs_modulus_pa > 0)) fail("Young's modulus", m.youngs_modulus_pa, "> 0 Pa");
  if (!(std::isfinite(m.poisson_ratio) && m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5))
    fail("Poisson ratio", m.poisson_ratio, "a value in (-1, 0.5) (0.5 is incompressible: no finite stiffness)");
  if (!(std::isfinite(m.rayleigh_alpha_per_s) && m.rayleigh_alpha_per_s >= 0))
    fail("Rayleigh alpha", m.rayleigh_alpha_per_s, ">= 0 1/s");
  if (!(std::isfinite(m.rayleigh_beta_s) && m.rayleigh_beta_s >= 0)) fail("Rayleigh beta", m.rayleigh_beta_s, ">= 0 s");
}

Eigen::Matrix<double, 6, 6> elasticityMatrix(const ElasticMaterial& m) {
  const double e = m.youngs_modulus_pa, nu = m.poisson_ratio;
  const double lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double mu = e / (2.0 * (1.0 + nu));
  Eigen::Matrix<double, 6, 6> d = Eigen::Matrix<double, 6, 6>::Zero();
  d.topLeftCorner<3, 3>().setConstant(lambda);
  for (int i = 0; i < 3; ++i) {
    d(i, i) = lambda + 2.0 * mu;
    d(3 + i, 3 + i) = mu;
  }
  return d;
}

}  // namespace thx::audio
