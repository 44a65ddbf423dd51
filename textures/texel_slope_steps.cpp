#include "textures/texel_slope_steps.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thx::tex {

namespace {
constexpr int kCodesPerOctave = 8;
constexpr int kCodeOfOne = 200;  // code 1 stands for 2^(-199/8), about 3e-8; code 254 for about 108
constexpr std::uint8_t kTooLarge = 255;
}  // namespace

double TexelSlopeSteps::decode(std::uint8_t code) {
  if (code == 0) return 0.0;
  if (code == kTooLarge) return std::numeric_limits<double>::infinity();
  return std::exp2(double(int(code) - kCodeOfOne) / kCodesPerOctave);
}

std::uint8_t TexelSlopeSteps::encode(double step) {
  if (!(step > 0.0)) return step == 0.0 ? 0 : kTooLarge;  // NaN: never within any angle
  if (!std::isfinite(step)) return kTooLarge;
  const double ideal = std::ceil(std::log2(step) * kCodesPerOctave) + kCodeOfOne;
  int code = int(std::clamp(ideal, 1.0, double(kTooLarge)));
  // log2 and exp2 round: step up until the code's bound covers the step.
  while (code < kTooLarge && decode(std::uint8_t(code)) < step) ++code;
  return std::uint8_t(code);
}

TexelSlopeSteps::TexelSlopeSteps(const TextureMap& map) : width_(map.width()), height_(map.height()) {
  for (int c = 0; c < 256; ++c) bounds_[std::size_t(c)] = decode(std::uint8_t(c));
  const std::size_t w = std::size_t(width_), h = std::size_t(height_);
  // Each texel's slope, in double from the float normal the renderers read, a row at a time: the
  // rows above, at and below the one whose steps are taken (a map may hold 2^28 texels).
  const auto slopesOf = [&map, w](std::size_t j, std::vector<Eigen::Vector2d>& row) {
    for (std::size_t i = 0; i < w; ++i) {
      const Eigen::Vector3d n = map.normal(int(i), int(j)).cast<double>();
      row[i] = Eigen::Vector2d(n.x() / n.z(), n.y() / n.z());
    }
  };
  std::vector<Eigen::Vector2d> above(w), here(w), below(w);
  slopesOf(h - 1, above);
  slopesOf(0, here);
  tiles_across_ = (w + kTile - 1) / kTile;
  const std::size_t tiles_down = (h + kTile - 1) / kTile;
  std::vector<double> tile_step2(tiles_across_ * tiles_down, 0.0);  // squared
  for (std::size_t j = 0; j < h; ++j) {
    slopesOf((j + 1) % h, below);
    for (std::size_t i = 0; i < w; ++i) {
      const Eigen::Vector2d& s = here[i];
      const Eigen::Vector2d* around[4] = {&here[(i + 1) % w], &here[(i + w - 1) % w], &below[i], &above[i]};
      double& step2 = tile_step2[(j / kTile) * tiles_across_ + i / kTile];
      for (const Eigen::Vector2d* n : around) step2 = std::max(step2, (s - *n).squaredNorm());
    }
    std::swap(above, here);
    std::swap(here, below);
  }
  codes_.resize(tile_step2.size());
  for (std::size_t t = 0; t < tile_step2.size(); ++t) codes_[t] = encode(std::sqrt(tile_step2[t]));
}

}  // namespace thx::tex
