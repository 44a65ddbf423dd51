#pragma once
// Relief maps (docs/audio.md §4b): the pen on a relief map follows the relief's geometry, and
// hapticd's CONTACT stream carries, every servo tick, the contact's normal n_k (the relief's
// normal under the tip), the base plane's normal n_g and the tip's tangential velocity v_k.
// Eq. 5 applied tick by tick: the normal momentum the relief gives the pen is
//   p(n) = m (-(v . n) / (n_g . n)) n_g,
// and each tick in contact after another applies
//   J_k = p_k(n_k) - p_k(n_{k-1}),  both at the current velocity v_k,
// so only the change of the relief's normal under the tip clicks (the hand's own acceleration
// does not): a flat relief, or a uniform slope, gives exactly 0. n_g . n is floored at
// min_normal_dot, which bounds |J| by 2 m |v| / min_normal_dot.
// The depth is used only to decide contact (depth > 0, i.e. the tick's in_contact).
#include <Eigen/Core>

namespace thx::audio {

struct ReliefTick {
  bool in_contact = false;
  Eigen::Vector3d geometric_normal{0.0, 0.0, 1.0};  // n_g (world frame), unit
  Eigen::Vector3d contact_normal{0.0, 0.0, 1.0};    // n_k (world frame), unit
  Eigen::Vector3d velocity{0.0, 0.0, 0.0};          // v_k, m/s (world frame); its n_g part is removed
};

// The impulse of tick `now` after tick `before` (N s along n_g, signed; 0 unless both are in
// contact). mass_kg: the pen's effective mass (docs/audio.md §5).
double reliefImpulse(const ReliefTick& before, const ReliefTick& now, double mass_kg, double min_normal_dot = 0.05);

}  // namespace thx::audio
