#include "scenes/materials.hpp"

namespace thx::scene {

const std::vector<Material>& materials() {
  // Source A = KleinPAT (Wang & James 2019) Table 4. Rows without published damping borrow it
  // from the nearest measured material, as docs/scenes.md "Materials" explains; porous materials
  // get a larger alpha because pores damp the low modes most.
  // clang-format off
  static const std::vector<Material> table = {
      // name           rho kg/m³  E Pa    nu     alpha 1/s beta s  mu    e     source of rho..beta
      {"ceramic",       2700,      7.2e10, 0.19,  6.0,      1e-7,   0.60, 0.60, "KleinPAT Table 4 (ceramic/porcelain)"},
      {"glass",         2600,      6.2e10, 0.20,  1.0,      1e-7,   0.50, 0.70, "KleinPAT Table 4"},
      {"wood",          750,       1.1e10, 0.25,  60.0,     2e-6,   0.60, 0.45, "KleinPAT Table 4"},
      {"plastic",       1070,      1.4e9,  0.35,  30.0,     1e-6,   0.50, 0.60, "KleinPAT Table 4"},
      {"polycarbonate", 1190,      2.4e9,  0.37,  0.5,      4e-7,   0.45, 0.65, "KleinPAT Table 4"},
      {"iron",          8000,      2.1e11, 0.28,  5.0,      1e-7,   0.60, 0.65, "KleinPAT Table 4"},
      {"steel",         7850,      2.0e11, 0.29,  5.0,      3e-8,   0.55, 0.75, "KleinPAT Table 4"},
      {"tin",           7265,      5.0e10, 0.325, 2.0,      3e-8,   0.60, 0.50, "PyModalSound"},
      {"aluminium",     2700,      7.0e10, 0.35,  5.0,      1e-7,   0.60, 0.60,
       "mesh2faust default (rho, E, nu); damping assumed = iron"},
      {"stone",         2700,      6.0e10, 0.25,  6.0,      1e-7,   0.70, 0.50,
       "granite handbook mid-range (recalled); damping assumed = ceramic"},
      {"brick",         1900,      1.5e10, 0.18,  30.0,     1e-7,   0.80, 0.40,
       "fired-clay handbook mid-range (recalled); damping = ceramic with alpha x5 (porous)"},
      {"concrete",      2400,      3.0e10, 0.20,  20.0,     1e-7,   0.80, 0.40,
       "handbook (recalled); damping = ceramic with alpha x3.3 (porous)"},
      // The study surfaces' materials (docs/scenes.md "Materials" names the pages).
      {"porcelain",     2400,      7.0e10, 0.17,  6.0,      1e-7,   0.50, 0.65,
       "material-properties.org (rho), MakeItFrom engineering porcelain (E low end, nu); damping = ceramic"},
      {"granite",       2700,      4.96e10, 0.213, 6.0,     1e-7,   0.70, 0.50,
       "Dowling Table 5.2 Westerly granite (E, nu), rho mid-range of granite/marble; damping = ceramic"},
      {"marble",        2700,      6.9e10, 0.281, 6.0,      1e-7,   0.50, 0.55,
       "Dowling Table 5.2 dolomitic limestone (E, nu), rho mid-range of granite/marble; damping = ceramic"},
      {"brass",         8500,      1.01e11, 0.35, 5.0,      3e-8,   0.50, 0.65,
       "Dowling Table 5.2 brass 70Cu-30Zn (E, nu), rho mid-range 8400-8600; damping = steel"},
      {"copper",        8900,      1.3e11, 0.343, 5.0,      3e-8,   0.55, 0.55,
       "Dowling Table 5.2 copper (E, nu), rho 8900; damping = steel"},
  };
  // clang-format on
  return table;
}

const Material* findMaterial(std::string_view name) {
  for (const Material& m : materials())
    if (m.name == name) return &m;
  return nullptr;
}

}  // namespace thx::scene
