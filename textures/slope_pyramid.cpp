#include "textures/slope_pyramid.hpp"

#include <algorithm>
#include <cmath>

namespace thx::tex {

SlopePyramid::SlopePyramid(const TextureMap& map, Address address) {
  Level base;
  base.width = map.width();
  base.height = map.height();
  base.slopes.resize(std::size_t(base.width) * std::size_t(base.height));
  Eigen::Vector2d total = Eigen::Vector2d::Zero();
  for (int j = 0; j < base.height; ++j)
    for (int i = 0; i < base.width; ++i) {
      const Eigen::Vector3f n = map.normal(i, j);
      const Eigen::Vector2f s(-n.x() / n.z(), -n.y() / n.z());
      base.slopes[std::size_t(j) * std::size_t(base.width) + std::size_t(i)] = s;
      total += s.cast<double>();
    }
  if (address == Address::Wrap) {
    const Eigen::Vector2f mean = (total / double(base.slopes.size())).cast<float>();
    for (Eigen::Vector2f& s : base.slopes) s -= mean;
  }
  levels_.push_back(std::move(base));
  while (levels_.back().width > 1 || levels_.back().height > 1) {
    const Level& fine = levels_.back();
    Level coarse;
    coarse.width = (fine.width + 1) / 2;
    coarse.height = (fine.height + 1) / 2;
    coarse.slopes.resize(std::size_t(coarse.width) * std::size_t(coarse.height));
    for (int j = 0; j < coarse.height; ++j)
      for (int i = 0; i < coarse.width; ++i) {
        // The mean of the (up to) four finer texels it covers: an odd side's last texel has one.
        Eigen::Vector2f sum = Eigen::Vector2f::Zero();
        int count = 0;
        for (int dj = 0; dj < 2; ++dj)
          for (int di = 0; di < 2; ++di) {
            const int fi = 2 * i + di, fj = 2 * j + dj;
            if (fi < fine.width && fj < fine.height) sum += fine.at(fi, fj), ++count;
          }
        coarse.slopes[std::size_t(j) * std::size_t(coarse.width) + std::size_t(i)] = sum / float(count);
      }
    levels_.push_back(std::move(coarse));
  }
}

Eigen::Vector2d SlopePyramid::bilinear(const Level& level, TexCoord uv, Address address) const {
  // Texel centres at (i + 0.5) / width along u, rows from v = 1 down (the map's convention).
  const double s = uv.u * level.width - 0.5, t = (1.0 - uv.v) * level.height - 0.5;
  const double s0 = std::floor(s), t0 = std::floor(t);
  const double fs = s - s0, ft = t - t0;
  const long long i0 = (long long)s0, j0 = (long long)t0;
  const int ia = resolveIndex(i0, level.width, address), ib = resolveIndex(i0 + 1, level.width, address);
  const int ja = resolveIndex(j0, level.height, address), jb = resolveIndex(j0 + 1, level.height, address);
  const Eigen::Vector2d top = (1.0 - fs) * level.at(ia, ja).cast<double>() + fs * level.at(ib, ja).cast<double>();
  const Eigen::Vector2d bottom = (1.0 - fs) * level.at(ia, jb).cast<double>() + fs * level.at(ib, jb).cast<double>();
  return (1.0 - ft) * top + ft * bottom;
}

Eigen::Vector2d SlopePyramid::slopes(TexCoord uv, double lod, Address address) const {
  // Far outside the map a clamped lookup is its edge; keep the index arithmetic defined.
  uv.u = std::clamp(uv.u, -1e6, 1e6);
  uv.v = std::clamp(uv.v, -1e6, 1e6);
  const double l = std::clamp(std::isfinite(lod) ? lod : 0.0, 0.0, double(levels() - 1));
  const int lo = int(std::floor(l)), hi = std::min(lo + 1, levels() - 1);
  const double f = l - double(lo);
  const Eigen::Vector2d a = bilinear(levels_[std::size_t(lo)], uv, address);
  return f > 0.0 ? Eigen::Vector2d((1.0 - f) * a + f * bilinear(levels_[std::size_t(hi)], uv, address)) : a;
}

Eigen::Vector3d SlopePyramid::normal(TexCoord uv, double lod, Address address) const {
  const Eigen::Vector2d s = slopes(uv, lod, address);
  return Eigen::Vector3d(-s.x(), -s.y(), 1.0).normalized();
}

}  // namespace thx::tex
