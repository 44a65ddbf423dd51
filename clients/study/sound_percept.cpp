#include "clients/study/sound_percept.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "clients/audio/synthesis/resonator_bank.hpp"
#include "clients/audio/synthesis/surface_sound.hpp"

namespace thx::study {

namespace {

// The top-face node nearest an off-centre point: the centre of a square slab lies on the nodal
// lines of many modes, which a struck bell or tile would not be struck on.
int strikeNode(const audio::TetMesh& mesh) {
  double top = -std::numeric_limits<double>::infinity();
  Eigen::Vector2d lo(1e9, 1e9), hi(-1e9, -1e9);
  for (const Eigen::Vector3d& p : mesh.nodes) {
    top = std::max(top, p.z());
    lo = lo.cwiseMin(p.head<2>());
    hi = hi.cwiseMax(p.head<2>());
  }
  const Eigen::Vector2d target = lo + Eigen::Vector2d(0.37, 0.29).cwiseProduct(hi - lo);
  int best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    const Eigen::Vector3d& p = mesh.nodes[i];
    if (p.z() < top - 1e-9 || (i < mesh.clamped.size() && mesh.clamped[i])) continue;
    const double d = (p.head<2>() - target).squaredNorm();
    if (d < best_d) best_d = d, best = int(i);
  }
  return best;
}

}  // namespace

std::optional<SoundPercept> hearSurface(const std::string& scene_path) {
  audio::SlabSettings s;
  s.cells = kPerceptSlabCells;
  s.layers = kPerceptSlabLayers;
  s.modes = kPerceptModes;
  s.no_cache = true;
  s.quiet = true;
  const audio::SurfaceSound sound = audio::buildSurfaceSound(scene_path, s);
  if (sound.scene.audio.mute || sound.modes.size() == 0) return std::nullopt;

  const audio::AudibleModes& m = sound.modes;
  audio::ResonatorBank bank(s.sample_rate_hz, m.size());
  if (!bank.setModes(m.frequency_hz, m.decay_per_s)) return std::nullopt;
  const int node = strikeNode(sound.slab);
  std::vector<double> g(m.size());
  for (std::size_t i = 0; i < m.size(); ++i) g[i] = -1e-3 * m.shapes(3 * node + 2, Eigen::Index(i));  // 1 mN s, downwards
  bank.strike(g);
  std::vector<double> x(std::size_t(kPerceptRenderS * s.sample_rate_hz));
  bank.render(x);

  return soundFeatures(x, s.sample_rate_hz);
}

std::optional<SoundPercept> soundFeatures(std::span<const double> x, double sample_rate_hz) {
  double e = 0.0, de = 0.0;
  for (std::size_t n = 0; n < x.size(); ++n) {
    e += x[n] * x[n];
    if (n + 1 < x.size()) de += (x[n + 1] - x[n]) * (x[n + 1] - x[n]);
  }
  if (!(e > 0.0)) return std::nullopt;
  SoundPercept p;
  // |1 - exp(-i w / fs)|² = 4 sin²(w / 2 fs): the differences' energy over the samples' gives the
  // spectrum's mean of that, inverted to a frequency.
  const double ratio = std::min(1.0, std::sqrt(de / e) / 2.0);
  p.pitch_log10_hz = std::log10(std::max(1.0, sample_rate_hz / std::numbers::pi * std::asin(ratio)));
  double tail = e;  // the energy from sample n on (Schroeder's backward integral)
  std::size_t n10 = x.size();
  for (std::size_t n = 0; n < x.size(); ++n) {
    if (tail <= 0.1 * e) {
      n10 = n;
      break;
    }
    tail -= x[n] * x[n];
  }
  p.ring_log10_s = std::log10(6.0 * double(n10) / sample_rate_hz);
  return p;
}

}  // namespace thx::study
