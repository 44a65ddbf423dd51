#pragma once
// The elastic and damping constants modal analysis needs, checked once with the object's name.
#include <Eigen/Core>
#include <string>

#include "scenes/materials.hpp"

namespace thx::audio {

struct ElasticMaterial {
  std::string name;
  double density_kg_per_m3 = 0.0;
  double youngs_modulus_pa = 0.0;
  double poisson_ratio = 0.0;
  double rayleigh_alpha_per_s = 0.0;  // C = alpha*M + beta*K
  double rayleigh_beta_s = 0.0;
};

ElasticMaterial fromSceneMaterial(const scene::Material& m);

// Throws ModalError naming `object` and the material unless rho > 0, E > 0, -1 < nu < 0.5,
// alpha >= 0 and beta >= 0 (all finite).
void checkMaterial(const std::string& object, const ElasticMaterial& m);

// Isotropic linear elasticity in Voigt order xx, yy, zz, yz, xz, xy (engineering shear strains).
Eigen::Matrix<double, 6, 6> elasticityMatrix(const ElasticMaterial& m);

}  // namespace thx::audio
