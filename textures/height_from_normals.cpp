#include "textures/height_from_normals.hpp"

#include <unsupported/Eigen/FFT>
#include <cmath>
#include <algorithm>
#include <complex>
#include <string>
#include <vector>

#include "textures/texture_error.hpp"

namespace thx::tex {

namespace {

using Complex = std::complex<double>;

// A row-major complex grid, transformed in place along rows then columns.
void fft2(std::vector<Complex>& grid, int width, int height, bool inverse) {
  Eigen::FFT<double> fft;
  std::vector<Complex> in, out;
  in.resize(std::size_t(std::max(width, height)));
  for (int j = 0; j < height; ++j) {
    in.assign(grid.begin() + std::ptrdiff_t(j) * width, grid.begin() + std::ptrdiff_t(j + 1) * width);
    inverse ? fft.inv(out, in) : fft.fwd(out, in);
    std::copy(out.begin(), out.end(), grid.begin() + std::ptrdiff_t(j) * width);
  }
  in.resize(std::size_t(height));
  for (int i = 0; i < width; ++i) {
    for (int j = 0; j < height; ++j) in[std::size_t(j)] = grid[std::size_t(j) * std::size_t(width) + std::size_t(i)];
    inverse ? fft.inv(out, in) : fft.fwd(out, in);
    for (int j = 0; j < height; ++j) grid[std::size_t(j) * std::size_t(width) + std::size_t(i)] = out[std::size_t(j)];
  }
}

}  // namespace

IntegratedNormals heightsFromNormals(const TextureMap& map, const Eigen::Vector2d& texel_m, Address address) {
  if (!(texel_m.allFinite() && texel_m.x() > 0.0 && texel_m.y() > 0.0))
    throw TextureError("heightsFromNormals", "texel size", std::to_string(texel_m.x()) + " x " + std::to_string(texel_m.y()) + " m",
                       "finite and > 0");
  const int w = map.width(), h = map.height();
  // Mirrored across the right and bottom borders for Clamp: heights even, so the slope across a
  // border changes sign.
  const bool mirror = address != Address::Wrap;
  const int W = mirror ? 2 * w : w, H = mirror ? 2 * h : h;
  // Slopes along +x (image right) in the real part and along the image's rows downwards (-y) in
  // the imaginary part: both real fields transformed as one (one grid in memory, not three).
  std::vector<Complex> grid(std::size_t(W) * std::size_t(H));
  for (int j = 0; j < H; ++j) {
    const int sj = j < h ? j : 2 * h - 1 - j;
    for (int i = 0; i < W; ++i) {
      const int si = i < w ? i : 2 * w - 1 - i;
      const Eigen::Vector3f n = map.normal(si, sj);
      const double nz = double(n.z());  // never below the map's flattest grazing normal
      grid[std::size_t(j) * std::size_t(W) + std::size_t(i)] =
          Complex((i < w ? 1.0 : -1.0) * -double(n.x()) / nz, (j < h ? 1.0 : -1.0) * double(n.y()) / nz);  // dh/d(row) = -dh/dy
    }
  }
  IntegratedNormals out;
  if (!mirror) {
    Complex sum = 0.0;
    for (const Complex& g : grid) sum += g;
    out.mean_slope = {sum.real() / double(grid.size()), -sum.imag() / double(grid.size())};
  }
  fft2(grid, W, H, false);
  // The central difference (f(x + d) - f(x - d)) / 2d has the symbol i sin(w) / d: the least-squares
  // heights are conj(Dx) Gx + conj(Dd) Gd over |Dx|^2 + |Dd|^2, nothing where both vanish (the mean,
  // and the Nyquist rows the central differences cannot see). Gx and Gd come out of the one
  // transform Z of gx + i gd by its symmetry: Gx(k) = (Z(k) + conj Z(-k)) / 2, Gd(k) = (Z(k) - conj Z(-k)) / 2i;
  // each frequency is solved with its mirror -k, both written back at once.
  const double negligible = 1e-12 * (1.0 / (texel_m.x() * texel_m.x()) + 1.0 / (texel_m.y() * texel_m.y()));
  auto at = [&](int i, int j) -> Complex& { return grid[std::size_t(j) * std::size_t(W) + std::size_t(i)]; };
  auto heightAt = [&](int i, int j, const Complex& z, const Complex& z_mirror) {
    const double sx = std::sin(2.0 * M_PI * i / W) / texel_m.x(), sy = std::sin(2.0 * M_PI * j / H) / texel_m.y();
    const double denominator = sx * sx + sy * sy;
    if (!(denominator > negligible)) return Complex(0.0, 0.0);
    const Complex gx = 0.5 * (z + std::conj(z_mirror)), gd = Complex(0.0, -0.5) * (z - std::conj(z_mirror));
    return (Complex(0.0, -sx) * gx + Complex(0.0, -sy) * gd) / denominator;
  };
  for (int j = 0; j < H; ++j) {
    const int mj = (H - j) % H;
    for (int i = 0; i < W; ++i) {
      const int mi = (W - i) % W;
      // Each pair once: the first of the two in row-major order.
      const std::size_t k = std::size_t(j) * std::size_t(W) + std::size_t(i), m = std::size_t(mj) * std::size_t(W) + std::size_t(mi);
      if (m < k) continue;
      const Complex z = at(i, j), z_mirror = at(mi, mj);
      at(i, j) = heightAt(i, j, z, z_mirror);
      if (m != k) at(mi, mj) = heightAt(mi, mj, z_mirror, z);
    }
  }
  fft2(grid, W, H, true);
  out.heights = HeightField(w, h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) out.heights.at(i, j) = at(i, j).real();
  return out;
}

ReliefOfNormals reliefFromNormals(const TextureMap& map, const Eigen::Vector2d& tile_m, Address address,
                                  const std::string& source) {
  const Eigen::Vector2d texel_m = tile_m.cwiseQuotient(Eigen::Vector2d(map.width(), map.height()));
  const IntegratedNormals integrated = heightsFromNormals(map, texel_m, address);
  ReliefFromHeightOptions o;
  o.texel_m = texel_m;
  o.address = address;
  o.source = source;
  return {reliefFromHeight(integrated.heights, o), integrated.mean_slope};
}

}  // namespace thx::tex
