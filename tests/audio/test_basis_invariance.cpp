// The sound does not depend on the basis the eigensolver returns inside a repeated mode's
// subspace (docs/audio.md §9a): every mode is heard through the body's listener w
// (observation.hpp) and a merge sums contributions, not shapes.
#include <gtest/gtest.h>

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <vector>

#include "clients/audio/audio_output.hpp"
#include "clients/audio/modal_body.hpp"
#include "clients/audio/modal_error.hpp"
#include "clients/audio/observation.hpp"
#include "clients/audio/resonator_bank.hpp"
#include "clients/audio/scene_bodies.hpp"
#include "clients/audio/wav_file.hpp"
#include "scenes/scene_loader.hpp"
#include "tests/audio/modal_fixtures.hpp"

namespace thx::audio {
namespace {

using test::steel;

constexpr double kRate = 44100.0;

// Runs of modes whose frequencies agree to 1e-8 (relative): the copies of a repeated eigenvalue.
std::vector<std::vector<int>> repeatedSets(const ModalSolution& s) {
  std::vector<std::vector<int>> sets;
  for (int k = 0; k < s.omega_rad_per_s.size(); ++k) {
    if (k > 0 && s.omega_rad_per_s[k] - s.omega_rad_per_s[k - 1] <= 1e-8 * s.omega_rad_per_s[k])
      sets.back().push_back(k);
    else
      sets.push_back({k});
  }
  std::erase_if(sets, [](const std::vector<int>& set) { return set.size() < 2; });
  return sets;
}

// An orthogonal n x n matrix from a seeded generator (QR of a matrix of uniform values; raw
// mt19937 words, so the same on every standard library).
Eigen::MatrixXd orthogonal(int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  Eigen::MatrixXd a(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) a(i, j) = double(rng()) / 4294967296.0 - 0.5;
  Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(a).householderQ();
  return q;
}

// The same solution with the columns of each set replaced by U Q: still M-orthonormal (Q is
// orthogonal) and, for a set of copies of one eigenvalue, still eigenvectors. The observation
// values follow as analyse() computes them: w . (U Q) = Q^T (U^T w).
ModalSolution rotated(ModalSolution s, const std::vector<std::vector<int>>& sets, std::uint32_t seed) {
  for (const std::vector<int>& set : sets) {
    const int n = int(set.size());
    const Eigen::MatrixXd q = orthogonal(n, seed++);
    Eigen::MatrixXd u(s.shapes.rows(), n);
    Eigen::VectorXd o(n);
    for (int j = 0; j < n; ++j) u.col(j) = s.shapes.col(set[std::size_t(j)]), o[j] = s.observation[set[std::size_t(j)]];
    const Eigen::MatrixXd uq = u * q;
    const Eigen::VectorXd oq = q.transpose() * o;
    for (int j = 0; j < n; ++j) s.shapes.col(set[std::size_t(j)]) = uq.col(j), s.observation[set[std::size_t(j)]] = oq[j];
  }
  return s;
}

// Largest change of a shape entry the rotation made, relative to the largest entry: the test is
// only meaningful when the basis really moved.
double basisChange(const ModalSolution& a, const ModalSolution& b) {
  return (a.shapes - b.shapes).cwiseAbs().maxCoeff() / a.shapes.cwiseAbs().maxCoeff();
}

struct Strike {
  Eigen::Vector3d point, impulse;
  std::size_t at;  // sample
};

// Strikes at points of the body (gainsAt), rendered by the resonator bank (double).
std::vector<double> render(const ModalBody& body, const std::vector<Strike>& strikes, std::size_t length) {
  ResonatorBank bank(kRate, body.size());
  EXPECT_TRUE(bank.setModes(body.modes().frequency_hz, body.modes().decay_per_s));
  std::vector<double> out(length, 0.0);
  std::size_t done = 0;
  for (const Strike& s : strikes) {
    bank.render(std::span<double>(out.data() + done, s.at - done));
    done = s.at;
    bank.strike(body.gainsAt(s.point, s.impulse));
  }
  bank.render(std::span<double>(out.data() + done, length - done));
  return out;
}

double peak(const std::vector<double>& x) {
  double p = 0;
  for (double v : x) p = std::max(p, std::fabs(v));
  return p;
}

double maxDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0;
  for (std::size_t k = 0; k < a.size(); ++k) d = std::max(d, std::fabs(a[k] - b[k]));
  return d;
}

// Points spread over the body's bounding box (taken at the mesh's nearest point when outside)
// struck in assorted directions.
std::vector<Strike> strikesOn(const TetMesh& mesh) {
  Eigen::Vector3d lo = mesh.nodes[0], hi = mesh.nodes[0];
  for (const Eigen::Vector3d& x : mesh.nodes) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  const double f[5][3] = {{0.1, 0.2, 0.9}, {0.8, 0.35, 0.05}, {0.45, 0.95, 0.6}, {0.02, 0.6, 0.3}, {0.7, 0.1, 0.75}};
  const Eigen::Vector3d d[5] = {{0.3, -0.2, 1.0}, {1.0, 0.4, -0.1}, {-0.5, 1.0, 0.2}, {0.1, 0.1, -1.0}, {0.6, -0.8, 0.5}};
  std::vector<Strike> strikes;
  for (int k = 0; k < 5; ++k) {
    const Eigen::Vector3d p = lo + (hi - lo).cwiseProduct(Eigen::Vector3d(f[k][0], f[k][1], f[k][2]));
    strikes.push_back({p, 1e-3 * d[k], std::size_t(300 * k)});
  }
  return strikes;
}

// Solved once per file (the shipped pen; a steel ball's 5-fold T2 and S2 families).
const ModalSolution& pen() {
  static const ModalSolution s = [] {
    ModalSettings ms;
    ms.elastic_modes = 20;
    const SceneBody b = penBody(scene::loadScene(std::string(THX_SOURCE_DIR) + "/scenes/default.yaml"));
    return analyse(b.mesh, b.material, ms);
  }();
  return s;
}
const SceneBody& penScene() {
  static const SceneBody b = penBody(scene::loadScene(std::string(THX_SOURCE_DIR) + "/scenes/default.yaml"));
  return b;
}
const TetMesh& sphereMeshOnce() {
  static const TetMesh m = sphereMesh("sphere", 0.1, 4, ElementOrder::Quadratic);
  return m;
}
const ModalSolution& sphere() {
  static const ModalSolution s = [] {
    ModalSettings ms;
    ms.elastic_modes = 10;
    return analyse(sphereMeshOnce(), steel(), ms);
  }();
  return s;
}

void expectSameSound(const TetMesh& mesh, const ElasticMaterial& material, const ModalSolution& a,
                     const ModalSolution& b, bool merge, const char* what) {
  AudibleOptions o;
  o.merge = merge;
  const ModalBody body_a(mesh, audibleModes(a, material, o)), body_b(mesh, audibleModes(b, material, o));
  ASSERT_EQ(body_a.size(), body_b.size()) << what;
  const std::vector<Strike> strikes = strikesOn(mesh);
  const std::vector<double> x = render(body_a, strikes, 8192), y = render(body_b, strikes, 8192);
  ASSERT_GT(peak(x), 0.0) << what;
  const double rel = maxDifference(x, y) / peak(x);
  std::printf("%s, merge %s: %zu audible modes, samples differ by %.2e of the peak\n", what, merge ? "on" : "off",
              body_a.size(), rel);
  // Merged, a repeated mode's copies are one resonator: only rounding differs. Unmerged, each copy
  // rings at its own frequency, and the solver's copies agree only to ~1e-11 (relative), so the
  // bases' sums drift apart by about 2 pi f df t, ~1e-9 over these 0.19 s.
  EXPECT_LT(rel, merge ? 1e-12 : 1e-8) << what;
}

TEST(BasisInvariance, RotatingThePensBendingPairsLeavesTheSoundUnchanged) {
  const ModalSolution& s = pen();
  const std::vector<std::vector<int>> sets = repeatedSets(s);
  ASSERT_GE(sets.size(), 3u);  // the square cross-section: bending pairs in x and y
  for (const auto& set : sets) EXPECT_EQ(set.size(), 2u);
  const ModalSolution r = rotated(s, sets, 7);
  EXPECT_GT(basisChange(s, r), 0.1);
  for (bool merge : {true, false}) expectSameSound(penScene().mesh, penScene().material, s, r, merge, "pen");
}

TEST(BasisInvariance, RotatingTheSpheresRepeatedModesLeavesTheSoundUnchanged) {
  const ModalSolution& s = sphere();
  const std::vector<std::vector<int>> sets = repeatedSets(s);
  // The cube-mapped mesh splits each 5-fold family into 2 + 3 exact copies (0.2 % apart).
  ASSERT_EQ(sets.size(), 4u);
  const ModalSolution r = rotated(s, sets, 11);
  EXPECT_GT(basisChange(s, r), 0.1);
  for (bool merge : {true, false}) expectSameSound(sphereMeshOnce(), steel(), s, r, merge, "sphere, 2 + 3 copies");
}

// Merging sums the members' contributions, so a merged mode is the same for any orthonormal basis
// of the members' span, even one mixing modes of different frequencies (not an eigenbasis).
TEST(BasisInvariance, AMergedQuintupletIsTheSameInAnyBasisOfItsSpan) {
  const ModalSolution& s = sphere();
  const ModalSolution r = rotated(s, {{0, 1, 2, 3, 4}, {5, 6, 7, 8, 9}}, 19);
  EXPECT_GT(basisChange(s, r), 0.1);
  expectSameSound(sphereMeshOnce(), steel(), s, r, true, "sphere, each quintuplet rotated as a whole");
}

TEST(BasisInvariance, AModesSignDoesNotChangeTheSound) {
  ModalSolution r = pen();
  for (int k = 0; k < r.omega_rad_per_s.size(); k += 3) r.shapes.col(k) *= -1.0, r.observation[k] *= -1.0;
  for (bool merge : {true, false}) expectSameSound(penScene().mesh, penScene().material, pen(), r, merge, "pen, signs");
}

// The observation functional on a hand-checked mesh: a 4 x 4 x 4-cell box has nodes at multiples
// of 0.5 of its half extents, so the targets of kPickupTargets pick the face-interior nodes
// (0.5, 0.5, 1), (-0.5, 0.5, -1), (1, -0.5, 0) and (0, -1, -0.5), whose normals are the faces'.
TEST(Observation, BoxPickupsAreTheNearestSurfaceNodesWithTheirFacesNormals) {
  const Eigen::Vector3d half(0.2, 0.15, 0.1);
  const TetMesh mesh = boxMesh("box", 2 * half, {4, 4, 4}, ElementOrder::Linear);
  const Eigen::Vector3d at[4] = {{0.5, 0.5, 1}, {-0.5, 0.5, -1}, {1, -0.5, 0}, {0, -1, -0.5}};
  const Eigen::Vector3d normal[4] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}};
  const std::vector<Pickup> ps = pickups(mesh);
  ASSERT_EQ(ps.size(), 4u);
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(mesh.dofCount());
  for (int k = 0; k < 4; ++k) {
    EXPECT_LT((mesh.nodes[std::size_t(ps[std::size_t(k)].node)] - at[k].cwiseProduct(half)).norm(), 1e-12) << k;
    EXPECT_LT((ps[std::size_t(k)].normal - normal[k]).norm(), 1e-12) << k;
    expected.segment<3>(3 * ps[std::size_t(k)].node) += 0.25 * normal[k];
  }
  // Weighted by the box's surface, 2 (0.4 x 0.3 + 0.4 x 0.2 + 0.3 x 0.2) = 0.52 m^2.
  EXPECT_NEAR(surfaceArea(mesh), 0.52, 1e-14);
  EXPECT_LT((observationVector(mesh) - 0.52 * expected).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(Observation, HeldNodesAreNeverPickups) {
  const TetMesh slab = slabMesh("slab", 0.2, 0.2, 0.01, {6, 6, 1}, ElementOrder::Linear, true);
  for (const Pickup& p : pickups(slab)) {
    EXPECT_FALSE(slab.clamped[std::size_t(p.node)]);
    EXPECT_NEAR(std::fabs(p.normal.z()), 1.0, 1e-12);  // on the top or bottom face
  }
  // Targets 1 and 2 on the top and bottom faces (docs/audio.md §9a's table).
  EXPECT_NEAR(pickups(slab)[0].normal.z(), 1.0, 1e-12);
  EXPECT_NEAR(pickups(slab)[1].normal.z(), -1.0, 1e-12);
  // A slab like the shipped one (Tet10, 2 layers): targets 3 and 4 on the +x and -y sides when
  // free; held, on the free top-face nodes next to those sides.
  for (bool clamp : {false, true}) {
    const TetMesh shipped = slabMesh("slab", 0.2, 0.2, 0.01, {6, 6, 2}, ElementOrder::Quadratic, clamp);
    const std::vector<Pickup> ps = pickups(shipped);
    if (!clamp) {
      EXPECT_NEAR(ps[2].normal.x(), 1.0, 1e-12);
      EXPECT_NEAR(ps[3].normal.y(), -1.0, 1e-12);
    } else {
      EXPECT_NEAR(ps[2].normal.z(), 1.0, 1e-12);
      EXPECT_NEAR(shipped.nodes[std::size_t(ps[2].node)].x(), 0.1 - 0.2 / 12, 1e-12);
      EXPECT_NEAR(std::fabs(ps[3].normal.z()), 1.0, 1e-12);
      EXPECT_NEAR(shipped.nodes[std::size_t(ps[3].node)].y(), -0.1 + 0.2 / 12, 1e-12);
    }
  }
  TetMesh held = slab;
  std::fill(held.clamped.begin(), held.clamped.end(), char(1));
  EXPECT_THROW(pickups(held), ModalError);
}

// The shipped pen (axis z, tip at -z): targets 1 and 2 on its end faces, 3 and 4 on its side,
// 3 above the middle and 4 towards the tip.
TEST(Observation, ThePensPickupsAreOnBothEndsAndItsSide) {
  const TetMesh& mesh = penScene().mesh;
  const std::vector<Pickup> ps = pickups(mesh);
  ASSERT_EQ(ps.size(), 4u);
  EXPECT_NEAR(ps[0].normal.z(), 1.0, 1e-9);
  EXPECT_NEAR(ps[1].normal.z(), -1.0, 1e-9);
  for (int k : {2, 3}) EXPECT_NEAR(ps[std::size_t(k)].normal.z(), 0.0, 1e-9) << k;
  EXPECT_GT(mesh.nodes[std::size_t(ps[2].node)].z(), 0.0);
  EXPECT_LT(mesh.nodes[std::size_t(ps[3].node)].z(), 0.0);
}

// Hand-made modes: each audible mode's column is u (w . u), so a strike J at a node drives it by
// (J . u)(w . u); a merged mode sums its members' such products.
TEST(Observation, AModeIsHeardAsItsDriveTimesItsObservation) {
  ModalSolution s;
  s.mesh_dofs = 6;
  s.omega_rad_per_s = Eigen::Vector3d(2 * std::numbers::pi * 1000, 2 * std::numbers::pi * 1001, 2 * std::numbers::pi * 3000);
  s.shapes.resize(6, 3);
  s.shapes.col(0) << 1, 2, 0, -1, 0.5, 3;
  s.shapes.col(1) << 0, 1, -2, 0.25, 1, 0;
  s.shapes.col(2) << 4, 0, 1, 0, -2, 1;
  s.observation = Eigen::Vector3d(0.5, -2.0, 0.1);
  ElasticMaterial m = steel();
  m.rayleigh_alpha_per_s = 0, m.rayleigh_beta_s = 0;
  const Eigen::Vector3d j(0.3, -0.7, 0.2);  // impulse at node 1 (DOFs 3..5)
  AudibleOptions o;
  o.merge = false;
  const AudibleModes single = audibleModes(s, m, o);
  ASSERT_EQ(single.size(), 3u);
  // Mode 0: J . u = 0.3 (-1) - 0.7 (0.5) + 0.2 (3) = -0.05, times w . u = 0.5.
  EXPECT_NEAR(single.shapes.row(3).col(0).value() * j.x() + single.shapes(4, 0) * j.y() + single.shapes(5, 0) * j.z(),
              -0.05 * 0.5, 1e-15);
  for (int k = 0; k < 3; ++k)
    EXPECT_LT((single.shapes.col(k) - s.shapes.col(k) * s.observation[k]).cwiseAbs().maxCoeff(), 1e-15);
  // 1000 and 1001 Hz merge (threshold 3 Hz): the column is the sum of the two products.
  const AudibleModes merged = audibleModes(s, m, AudibleOptions{});
  ASSERT_EQ(merged.size(), 2u);
  EXPECT_EQ(merged.members[0], 2);
  const Eigen::VectorXd sum = s.shapes.col(0) * 0.5 + s.shapes.col(1) * -2.0;
  EXPECT_LT((merged.shapes.col(0) - sum).cwiseAbs().maxCoeff(), 1e-15);
  // No observation values: refused, not guessed.
  s.observation.resize(0);
  EXPECT_THROW(audibleModes(s, m, o), std::invalid_argument);
}

// The shipped pen solved with CHOLMOD's supernodal Cholesky and with Eigen's LDL^T (modal-analyze
// --factorization) returns each bending pair in another basis; the pen struck at its tip and along
// its side gives the same WAV from both.
TEST(BasisInvariance, ThePenSoundsTheSameFromCholmodAndLdltSolves) {
  const SceneBody& b = penScene();
  ModalSettings ms;
  ms.elastic_modes = 20;
  const ModalSolution cholmod = pen();
  ms.factorization = Factorization::SimplicialLdlt;
  const ModalSolution ldlt = analyse(b.mesh, b.material, ms);
  ASSERT_EQ(cholmod.omega_rad_per_s.size(), ldlt.omega_rad_per_s.size());
  const std::string dir = ::testing::TempDir() + "basis_invariance";
  std::filesystem::create_directories(dir);
  auto wav = [&](const ModalSolution& s, bool listened, const std::string& name) {
    ModalSolution heard = s;
    // Without the listener (every w . u_i = 1) the shapes are summed as before this change.
    if (!listened) heard.observation.setOnes();
    const ModalBody body(b.mesh, audibleModes(heard, b.material, AudibleOptions{}));
    std::vector<Strike> strikes = strikesOn(b.mesh);
    strikes.insert(strikes.begin(), {b.mesh.nodes[std::size_t(penTipNode(b.mesh))], {5e-4, 0, 8.7e-4}, 0});
    const std::vector<double> x = render(body, strikes, 8192);
    const double p = peak(x);
    std::vector<float> f(x.size());
    for (std::size_t k = 0; k < x.size(); ++k) f[k] = float(0.5 * x[k] / p);
    const std::string path = dir + "/" + name + ".wav";
    {
      WavWriter w(path, int(kRate));
      w.write(f);
    }
    return std::pair{readMonoSound(path).samples, p};
  };
  const auto [a, peak_a] = wav(cholmod, true, "cholmod");
  const auto [c, peak_c] = wav(ldlt, true, "ldlt");
  ASSERT_EQ(a.size(), c.size());
  double diff = 0;
  for (std::size_t k = 0; k < a.size(); ++k) diff = std::max(diff, double(std::fabs(a[k] - c[k])));
  const auto [old_a, old_peak_a] = wav(cholmod, false, "cholmod_unobserved");
  const auto [old_c, old_peak_c] = wav(ldlt, false, "ldlt_unobserved");
  double old_diff = 0;
  for (std::size_t k = 0; k < old_a.size(); ++k) old_diff = std::max(old_diff, double(std::fabs(old_a[k] - old_c[k])));
  std::printf("pen, cholmod vs ldlt: raw peaks %.6e / %.6e, WAV samples differ by %.2e (peak 0.5); "
              "summed shapes without the listener: raw peaks %.6e / %.6e, differ by %.2e\n",
              peak_a, peak_c, diff, old_peak_a, old_peak_c, old_diff);
  EXPECT_NEAR(peak_a / peak_c, 1.0, 1e-8);
  EXPECT_LT(diff, 1e-6);
}

}  // namespace
}  // namespace thx::audio
