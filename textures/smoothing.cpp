#include "textures/smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "textures/texture_error.hpp"

namespace thx::tex {

namespace {

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// One channel of the map, row-major, in double.
using Channel = std::vector<double>;

// The texel a filter tap reads at index i of n: Wrap tiles the map (a tiling map stays seamless),
// Clamp repeats the edge texel.
int tapIndex(int i, int n, Address address) {
  if (address == Address::Wrap) return ((i % n) + n) % n;
  return std::clamp(i, 0, n - 1);
}

// The normalised Gaussian of 2 radius + 1 taps.
std::vector<double> gaussianKernel(int radius, double sigma) {
  std::vector<double> k(std::size_t(2 * radius + 1));
  double sum = 0.0;
  for (int t = -radius; t <= radius; ++t) sum += k[std::size_t(t + radius)] = std::exp(-0.5 * t * t / (sigma * sigma));
  for (double& v : k) v /= sum;
  return k;
}

// Separable blur: along x, then along y, each tap through the address mode's border.
Channel blur(const Channel& in, int w, int h, const std::vector<double>& kernel, Address address) {
  const int radius = int(kernel.size() / 2);
  Channel rows(in.size()), out(in.size());
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      double acc = 0.0;
      for (int t = -radius; t <= radius; ++t)
        acc += kernel[std::size_t(t + radius)] * in[std::size_t(j) * std::size_t(w) + std::size_t(tapIndex(i + t, w, address))];
      rows[std::size_t(j) * std::size_t(w) + std::size_t(i)] = acc;
    }
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      double acc = 0.0;
      for (int t = -radius; t <= radius; ++t)
        acc += kernel[std::size_t(t + radius)] * rows[std::size_t(tapIndex(j + t, h, address)) * std::size_t(w) + std::size_t(i)];
      out[std::size_t(j) * std::size_t(w) + std::size_t(i)] = acc;
    }
  return out;
}

}  // namespace

TextureMap smoothTexture(const TextureMap& map, const SmoothOptions& options) {
  const std::string source = "smoothing";
  if (map.width() <= 0 || map.height() <= 0) throw TextureError(source, "empty texture", "0x0", "a loaded texture");
  if (!std::isfinite(options.sigma_texels) || options.sigma_texels < 0.0 ||
      options.sigma_texels > kMaxSmoothingSigma) {
    throw TextureError(source, "sigma out of range", "sigma=" + fmt(options.sigma_texels),
                       "a finite value in [0, " + fmt(kMaxSmoothingSigma) + "] texels");
  }
  if (!std::isfinite(options.max_slope) || !(options.max_slope > 0.0)) {
    throw TextureError(source, "slope bound out of range", "max_slope=" + fmt(options.max_slope),
                       "a finite value > 0");
  }
  if (options.sigma_texels == 0.0) return map;

  const int w = map.width(), h = map.height();
  const std::size_t texels = std::size_t(w) * std::size_t(h);
  Channel sx(texels), sy(texels), depth(texels);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const std::size_t at = std::size_t(j) * std::size_t(w) + std::size_t(i);
      const Eigen::Vector3f n = map.normal(i, j);
      const double nz = std::max(double(n.z()), 1e-9);  // stored normals have nz > 0; guard anyway
      sx[at] = std::clamp(-double(n.x()) / nz, -options.max_slope, options.max_slope);
      sy[at] = std::clamp(-double(n.y()) / nz, -options.max_slope, options.max_slope);
      depth[at] = map.depth(i, j);
    }
  }

  const std::vector<double> kernel = gaussianKernel(int(std::ceil(4.0 * options.sigma_texels)), options.sigma_texels);
  sx = blur(sx, w, h, kernel, options.address);
  sy = blur(sy, w, h, kernel, options.address);
  if (map.isRelief()) depth = blur(depth, w, h, kernel, options.address);

  TextureMap out(w, h, map.representation(), map.maxDepth());
  out.meta() = map.meta();
  out.meta().params += std::string(out.meta().params.empty() ? "" : " ") + "smoothed sigma=" +
                       fmt(options.sigma_texels) +
                       (options.address == Address::Wrap ? " address=wrap" : " address=clamp");
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const std::size_t at = std::size_t(j) * std::size_t(w) + std::size_t(i);
      out.setNormal(i, j, Eigen::Vector3f(float(-sx[at]), float(-sy[at]), 1.0f));
      if (map.isRelief()) out.setDepth(i, j, depth[at]);
    }
  }
  return out;
}

}  // namespace thx::tex
