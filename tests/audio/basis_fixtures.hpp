#pragma once
// Shared by test_basis_invariance.cpp and its slow twin: rotations of a solution's repeated modes,
// strikes rendered through the resonator bank, and the same body solved with both factorizations
// and written as WAVs (docs/audio.md §9a).
#include <gtest/gtest.h>

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "clients/audio/analysis/modal_body.hpp"
#include "clients/audio/live/audio_output.hpp"
#include "clients/audio/spectrogram/wav_file.hpp"
#include "clients/audio/synthesis/resonator_bank.hpp"

namespace thx::audio::test {

inline constexpr double kRate = 44100.0;

// Runs of modes whose frequencies agree to 1e-8 (relative): the copies of a repeated eigenvalue.
inline std::vector<std::vector<int>> repeatedSets(const ModalSolution& s) {
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
inline Eigen::MatrixXd orthogonal(int n, std::uint32_t seed) {
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
inline ModalSolution rotated(ModalSolution s, const std::vector<std::vector<int>>& sets, std::uint32_t seed) {
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
inline double basisChange(const ModalSolution& a, const ModalSolution& b) {
  return (a.shapes - b.shapes).cwiseAbs().maxCoeff() / a.shapes.cwiseAbs().maxCoeff();
}

struct Strike {
  Eigen::Vector3d point, impulse;
  std::size_t at;  // sample
};

// Strikes at points of the body (gainsAt), rendered by the resonator bank (double).
inline std::vector<double> render(const ModalBody& body, const std::vector<Strike>& strikes, std::size_t length) {
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

inline double peak(const std::vector<double>& x) {
  double p = 0;
  for (double v : x) p = std::max(p, std::fabs(v));
  return p;
}

inline double maxDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0;
  for (std::size_t k = 0; k < a.size(); ++k) d = std::max(d, std::fabs(a[k] - b[k]));
  return d;
}

// Points spread over the body's bounding box (taken at the mesh's nearest point when outside)
// struck in assorted directions.
inline std::vector<Strike> strikesOn(const TetMesh& mesh) {
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

inline void expectSameSound(const TetMesh& mesh, const ElasticMaterial& material, const ModalSolution& a,
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

// `mesh` solved with CHOLMOD's supernodal Cholesky and with Eigen's LDL^T (modal-analyze
// --factorization), struck at `tip` and at strikesOn's points, written as WAVs normalised to 0.5
// and read back: the largest sample difference with the listener, and without it (every w . u_i
// = 1: the shapes summed as before docs/audio.md §9a).
struct FactorizationComparison {
  double listened = 0, unobserved = 0;
};

inline FactorizationComparison compareFactorizations(const TetMesh& mesh, const ElasticMaterial& material,
                                                     const Eigen::Vector3d& tip, int modes, const std::string& name) {
  ModalSettings ms;
  ms.elastic_modes = modes;
  const ModalSolution cholmod = analyse(mesh, material, ms);
  ms.factorization = Factorization::SimplicialLdlt;
  const ModalSolution ldlt = analyse(mesh, material, ms);
  EXPECT_EQ(cholmod.omega_rad_per_s.size(), ldlt.omega_rad_per_s.size());
  const std::string dir = ::testing::TempDir() + "basis_invariance_" + name;
  std::filesystem::create_directories(dir);
  auto wav = [&](const ModalSolution& s, bool listened, const std::string& file) {
    ModalSolution heard = s;
    if (!listened) heard.observation.setOnes();
    const ModalBody body(mesh, audibleModes(heard, material, AudibleOptions{}));
    std::vector<Strike> strikes = strikesOn(mesh);
    strikes.insert(strikes.begin(), {tip, {5e-4, 0, 8.7e-4}, 0});
    const std::vector<double> x = render(body, strikes, 8192);
    const double p = peak(x);
    std::vector<float> f(x.size());
    for (std::size_t k = 0; k < x.size(); ++k) f[k] = float(0.5 * x[k] / p);
    const std::string path = dir + "/" + file + ".wav";
    {
      WavWriter w(path, int(kRate));
      w.write(f);
    }
    return readMonoSound(path).samples;
  };
  auto difference = [](const std::vector<float>& a, const std::vector<float>& b) {
    EXPECT_EQ(a.size(), b.size());
    double d = 0;
    for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) d = std::max(d, double(std::fabs(a[k] - b[k])));
    return d;
  };
  FactorizationComparison c;
  c.listened = difference(wav(cholmod, true, "cholmod"), wav(ldlt, true, "ldlt"));
  c.unobserved = difference(wav(cholmod, false, "cholmod_unobserved"), wav(ldlt, false, "ldlt_unobserved"));
  std::printf("%s, cholmod vs ldlt: WAV samples (peak 0.5) differ by %.2e; summing shapes without the listener: %.2e\n",
              name.c_str(), c.listened, c.unobserved);
  return c;
}

}  // namespace thx::audio::test
