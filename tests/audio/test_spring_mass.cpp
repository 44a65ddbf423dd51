// The spring-mass lattice (clients/audio/analysis/spring_mass.hpp) against closed forms: a chain of N free
// masses held at both ends has omega_j = 2 sqrt(k/m) sin(j pi / (2 (N + 1))); a free chain of N
// masses omega_j = 2 sqrt(k/m) sin(j pi / (2 N)) with j = 0 the rigid translation; a held
// rectangular lattice the sum of two chains' squared frequencies.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "clients/audio/analysis/modal_error.hpp"
#include "clients/audio/analysis/spring_mass.hpp"
#include "scenes/materials.hpp"

namespace thx::audio::test_spring_mass {
namespace {

constexpr double kPi = std::numbers::pi;

SpringMassLattice chain(int nodes, double m, double k, bool clamp) {
  SpringMassLattice l;
  l.name = "chain";
  l.nx = nodes;
  l.ny = 1;
  l.mass_kg = m;
  l.spring_n_per_m = k;
  l.clamp_edges = clamp;
  return l;
}

ModalSettings settingsFor(int modes, double shift_hz) {
  ModalSettings s;
  s.elastic_modes = modes;
  s.shift_hz = shift_hz;
  return s;
}

TEST(SpringMass, HeldChainMatchesTheClosedForm) {
  // 40 nodes, both ends held: N = 38 free masses.
  const double m = 0.01, k = 4.0e4;
  const int free_masses = 38;
  const ModalSolution s = springMassModes(chain(free_masses + 2, m, k, true), settingsFor(8, 1.0));
  EXPECT_EQ(s.rigid_modes, 0);
  EXPECT_EQ(s.free_dofs, free_masses);
  EXPECT_EQ(s.mesh_dofs, free_masses + 2);
  ASSERT_EQ(s.omega_rad_per_s.size(), 8);
  for (int j = 1; j <= 8; ++j) {
    const double expected = 2 * std::sqrt(k / m) * std::sin(j * kPi / (2.0 * (free_masses + 1)));
    EXPECT_NEAR(s.omega_rad_per_s[j - 1] / expected, 1.0, 1e-9) << "mode " << j;
  }
  // Held ends do not move; the shapes are mass-orthonormal.
  EXPECT_EQ(s.shapes(0, 0), 0.0);
  EXPECT_EQ(s.shapes(free_masses + 1, 3), 0.0);
  const Eigen::MatrixXd gram = m * s.shapes.transpose() * s.shapes;
  EXPECT_TRUE(gram.isIdentity(1e-8)) << gram;
}

TEST(SpringMass, FreeChainDropsOneRigidModeAndMatchesTheClosedForm) {
  const double m = 0.002, k = 1.0e3;
  const int n = 30;
  const ModalSolution s = springMassModes(chain(n, m, k, false), settingsFor(6, 1.0));
  EXPECT_EQ(s.rigid_modes, 1);
  EXPECT_NEAR(s.rigid_hz[0], 0.0, 1e-3);
  for (int j = 1; j <= 6; ++j) {
    const double expected = 2 * std::sqrt(k / m) * std::sin(j * kPi / (2.0 * n));
    EXPECT_NEAR(s.omega_rad_per_s[j - 1] / expected, 1.0, 1e-9) << "mode " << j;
  }
}

TEST(SpringMass, HeldLatticeIsTheSumOfTwoChains) {
  const double m = 0.5, k = 2.0e3;
  const int nx = 12, ny = 9;  // 10 x 7 free masses
  SpringMassLattice l = chain(nx, m, k, true);
  l.name = "lattice";
  l.ny = ny;
  const ModalSolution s = springMassModes(l, settingsFor(10, 1.0));
  std::vector<double> expected;
  for (int p = 1; p <= nx - 2; ++p)
    for (int q = 1; q <= ny - 2; ++q) {
      const double a = std::sin(p * kPi / (2.0 * (nx - 1))), b = std::sin(q * kPi / (2.0 * (ny - 1)));
      expected.push_back(2 * std::sqrt(k / m) * std::sqrt(a * a + b * b));
    }
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(s.free_dofs, (nx - 2) * (ny - 2));
  for (int j = 0; j < 10; ++j) EXPECT_NEAR(s.omega_rad_per_s[j] / expected[std::size_t(j)], 1.0, 1e-9) << "mode " << j;
}

TEST(SpringMass, SurfaceLatticeTakesMassAndStiffnessFromTheMaterial) {
  const scene::Material steel = *scene::findMaterial("steel");
  const SpringMassLattice l = surfaceLattice("plate", 0.2, 0.1, 0.005, 11, steel, true);
  EXPECT_EQ(l.nx, 11);
  EXPECT_EQ(l.ny, 11);
  EXPECT_NEAR(l.mass_kg, steel.density_kg_per_m3 * 0.005 * 0.02 * 0.01, 1e-15);
  EXPECT_NEAR(l.spring_n_per_m, steel.youngs_modulus_pa * 0.005, 1e-3);
  const SpringMassSystem sys = assembleSpringMass(l);
  EXPECT_EQ(sys.free_count, 81);
  // Each row of K sums to k times the number of held neighbours (0 inside the lattice).
  const Eigen::VectorXd row_sums = sys.stiffness * Eigen::VectorXd::Ones(sys.free_count);
  EXPECT_NEAR(row_sums[sys.free_dof[5 * 11 + 5]], 0.0, 1e-6);
  EXPECT_NEAR(row_sums[sys.free_dof[1 * 11 + 1]], 2 * l.spring_n_per_m, 1e-3);  // a corner: two held neighbours
}

TEST(SpringMass, BadInputIsRefusedWithTheObjectNamed) {
  EXPECT_THROW(assembleSpringMass(chain(1, 1, 1, false)), ModalError);
  EXPECT_THROW(assembleSpringMass(chain(5, 0, 1, false)), ModalError);
  EXPECT_THROW(assembleSpringMass(chain(2, 1, 1, true)), ModalError);  // both nodes held
  try {
    springMassModes(chain(6, 1, 1, true), settingsFor(10, 1.0));
    FAIL() << "more modes than free nodes was accepted";
  } catch (const ModalError& e) {
    EXPECT_NE(std::string(e.what()).find("chain"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace thx::audio::test_spring_mass
