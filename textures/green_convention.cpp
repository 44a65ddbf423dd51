#include "textures/green_convention.hpp"

#include <cmath>
#include <vector>

namespace thx::tex {

GreenGuess guessGreenConvention(const TextureMap& map, GreenConvention read_as) {
  const int w = map.width(), h = map.height();
  // Slopes of the height field (per unit length along x and y; the texel size scales both sums
  // alike and does not change the sign).
  std::vector<double> p(std::size_t(w) * std::size_t(h)), q(p.size());
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const Eigen::Vector3f n = map.normal(i, j);
      p[std::size_t(j) * std::size_t(w) + std::size_t(i)] = -double(n.x()) / double(n.z());
      q[std::size_t(j) * std::size_t(w) + std::size_t(i)] = -double(n.y()) / double(n.z());
    }
  }
  auto at = [&](const std::vector<double>& f, int i, int j) { return f[std::size_t(j) * std::size_t(w) + std::size_t(i)]; };
  double cross = 0.0, magnitude = 0.0;
  for (int j = 1; j + 1 < h; ++j) {
    for (int i = 1; i + 1 < w; ++i) {
      const double dq_dx = at(q, i + 1, j) - at(q, i - 1, j);
      const double dp_dy = at(p, i, j - 1) - at(p, i, j + 1);  // +y = image up = decreasing row
      cross += dq_dx * dp_dy;
      magnitude += std::fabs(dq_dx * dp_dy);
    }
  }
  GreenGuess guess;
  if (!(magnitude > 1e-12)) return guess;
  guess.score = cross / magnitude;
  const GreenConvention other = read_as == GreenConvention::OpenGL ? GreenConvention::DirectX : GreenConvention::OpenGL;
  if (guess.score >= kGreenGuessMinScore) guess.convention = read_as;
  if (guess.score <= -kGreenGuessMinScore) guess.convention = other;
  return guess;
}

}  // namespace thx::tex
