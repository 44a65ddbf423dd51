#pragma once
// Normal-map images built inside the tests: a Gaussian bump's exact normals, encoded in either
// green convention, and a TGA file written by hand (an 18-byte header and raw pixels).
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace thx::tex::test {

// A bump of height 0.3 texel-widths·n/8 and width n/8 centred on an n x n image: slopes up to
// about 0.36 (20°), mixed slopes everywhere off the axes. Texel (i, j), row 0 at the top, +y up.
inline Eigen::Vector3f bumpNormal(int i, int j, int n) {
  const double c = 0.5 * (n - 1), s = n / 8.0, a = 0.3 * s * 2.0;
  const double x = i - c, y = c - j;  // +y = image up
  const double h = a * std::exp(-(x * x + y * y) / (2 * s * s));
  const double hx = -x / (s * s) * h, hy = -y / (s * s) * h;
  return Eigen::Vector3d(-hx, -hy, 1.0).normalized().cast<float>();
}

// Straight grooves along y: slopes only along x, no mixed slopes.
inline Eigen::Vector3f grooveNormal(int i, int /*j*/, int n) {
  const double hx = 0.4 * std::sin(2 * M_PI * i * 4.0 / n);
  return Eigen::Vector3d(-hx, 0.0, 1.0).normalized().cast<float>();
}

// 8-bit code of one normal component, (n + 1)/2 · 255.
inline std::uint8_t code8(float c) { return std::uint8_t(std::lround((c + 1.0) * 0.5 * 255.0)); }

// Pixels (R, G, B[, A]) of an n x n bump, row 0 at the top; DirectX stores -y in green.
inline std::vector<std::uint8_t> bumpRgb(int n, bool directx, int alpha = -1) {
  std::vector<std::uint8_t> px;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3f v = bumpNormal(i, j, n);
      px.push_back(code8(v.x()));
      px.push_back(code8(directx ? -v.y() : v.y()));
      px.push_back(code8(v.z()));
      if (alpha >= 0) px.push_back(std::uint8_t(alpha));
    }
  }
  return px;
}

// An uncompressed true-colour TGA (image type 2) of RGB or RGBA pixels given top row first,
// stored bottom row first (the usual TGA origin; descriptor bit 5 clear).
inline void writeTga(const std::string& path, int w, int h, int channels, const std::vector<std::uint8_t>& rgba,
                     std::size_t keep_bytes = std::size_t(-1)) {
  std::vector<std::uint8_t> bytes = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0,
                                     std::uint8_t(w & 255), std::uint8_t(w >> 8), std::uint8_t(h & 255),
                                     std::uint8_t(h >> 8), std::uint8_t(8 * channels),
                                     std::uint8_t(channels == 4 ? 8 : 0)};
  for (int j = h - 1; j >= 0; --j) {
    for (int i = 0; i < w; ++i) {
      const std::uint8_t* p = &rgba[(std::size_t(j) * std::size_t(w) + std::size_t(i)) * std::size_t(channels)];
      bytes.push_back(p[2]);  // TGA stores BGR(A)
      bytes.push_back(p[1]);
      bytes.push_back(p[0]);
      if (channels == 4) bytes.push_back(p[3]);
    }
  }
  if (keep_bytes < bytes.size()) bytes.resize(keep_bytes);
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// Largest angle between two fields of normals, degrees.
template <class MapA, class Fn>
double maxAngleDeg(const MapA& map, Fn expected) {
  double worst = 0.0;
  for (int j = 0; j < map.height(); ++j) {
    for (int i = 0; i < map.width(); ++i) {
      const double dot = std::clamp(double(map.normal(i, j).dot(expected(i, j))), -1.0, 1.0);
      worst = std::max(worst, std::acos(dot) * 180.0 / M_PI);
    }
  }
  return worst;
}

}  // namespace thx::tex::test
