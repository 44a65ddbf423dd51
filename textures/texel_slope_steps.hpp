#pragma once
// How sharply a texture's normals turn between neighbouring texels, read once when a surface is
// built so that the servo can skip reading a texel's neighbourhood where nothing there can form
// a crease (server/proxy_renderer.hpp, planesAround).
//
// For each texel, an upper bound on the slope step to its four neighbours: the largest
// |s(texel) - s(neighbour)|, where s = (n_x / n_z, n_y / n_z) is the relief's slope that the
// stored normal stands for (as TextureMap::normal decodes it), neighbours taken across the map's
// edges as Address::Wrap does. Two normals whose slopes, each scaled by at most c along x and y,
// differ by at most d turn by at most asin(c d) (their vectors (c_x s_x, c_y s_y, 1) differ by at
// most c d, and each is at least 1 long), so a renderer that knows its surface's slope scale and
// its crease angle can tell from one byte that every neighbour is within the angle.
//
// Stored as one byte per tile of 4 x 4 texels (the largest step of the tile's texels), on a
// logarithmic scale (eight codes per octave), always rounded up: bound() is never below the step
// as computed. Code 0 is a step of exactly zero, 255 a step too large to be worth a code (bound()
// is infinite). A 1024 x 1024 map's steps take 64 KiB (the map itself 6 MiB; hapticd's resident
// memory has a budget, docs/benchmarks.md); a tile holding a crease loses the shortcut for its
// smooth texels too. Built offline (allocates); reading it is real-time safe.
#include <array>
#include <cstdint>
#include <vector>

#include "textures/texture_map.hpp"

namespace thx::tex {

class TexelSlopeSteps {
 public:
  TexelSlopeSteps() = default;
  explicit TexelSlopeSteps(const TextureMap& map);

  int width() const { return width_; }
  int height() const { return height_; }
  static constexpr int kTile = 4;  // texels along each side of a tile
  // An upper bound on the slope step from texel (i, j) (resolved: 0 <= i < width) to any of its
  // four neighbours.
  double bound(int i, int j) const {
    return bounds_[codes_[std::size_t(j / kTile) * tiles_across_ + std::size_t(i / kTile)]];
  }
  std::size_t bytes() const { return codes_.size(); }

  // The code a step is stored as, and the bound a code stands for (public for the tests).
  static std::uint8_t encode(double step);
  static double decode(std::uint8_t code);

 private:
  int width_ = 0;
  int height_ = 0;
  std::size_t tiles_across_ = 0;
  std::vector<std::uint8_t> codes_;  // a tile's, row by row
  std::array<double, 256> bounds_{};  // decode(code), read without a call in the servo
};

}  // namespace thx::tex
