#pragma once
// The elastic and damping constants modal analysis needs, checked once with the object's name.
#include <Eigen/Core>
#include <string>

#include "scenes/materials.hpp"

namespace thx::audio {

// The scenes' own material (one table for every sense): modal analysis reads its density, elastic
// constants and Rayleigh damping, and ignores the Bullet coefficients.
using ElasticMaterial = scene::Material;

// Throws ModalError naming `object` and the material unless rho > 0, E > 0, -1 < nu < 0.5,
// alpha >= 0 and beta >= 0 (all finite).
void checkMaterial(const std::string& object, const ElasticMaterial& m);

// Isotropic linear elasticity in Voigt order xx, yy, zz, yz, xz, xy (engineering shear strains).
Eigen::Matrix<double, 6, 6> elasticityMatrix(const ElasticMaterial& m);

}  // namespace thx::audio
