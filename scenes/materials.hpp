#pragma once
// The material table shared by sound (modal synthesis) and physics (Bullet contacts).
// Elastic and damping values are from the sources in docs/scenes.md "Materials"; friction and
// restitution are our choice (docs/scenes.md §materials says why and how Bullet combines them).
#include <string>
#include <string_view>
#include <vector>

namespace thx::scene {

struct Material {
  std::string name;
  double density_kg_per_m3 = 0.0;
  double youngs_modulus_pa = 0.0;
  double poisson_ratio = 0.0;
  // Rayleigh damping C = alpha*M + beta*K (mode decay d = (alpha + beta*omega^2) / 2).
  double rayleigh_alpha_per_s = 0.0;
  double rayleigh_beta_s = 0.0;
  // Per-body Bullet coefficients; Bullet multiplies the two bodies' values at a contact.
  double friction = 0.0;
  double restitution = 0.0;
  std::string source;  // where the elastic and damping values come from
  // Bullet's rolling friction, a length: the rolling-resistance torque is at most this times the
  // normal force. Bullet combines a pair as delta_a * mu_b + delta_b * mu_a. 0 in the table (a
  // scene sets it: `material: {name: steel, rolling_friction: 1e-4}`).
  double rolling_friction_m = 0.0;
  // Bullet's spinning (torsional) friction, a length: the torque resisting a spin about the
  // contact normal is at most this times the normal force; combined like rolling friction. 0 in
  // the table (a scene sets it: `material: {name: glass, spinning_friction: 1e-4}`).
  double spinning_friction_m = 0.0;
};

const std::vector<Material>& materials();
const Material* findMaterial(std::string_view name);  // nullptr if unknown

}  // namespace thx::scene
