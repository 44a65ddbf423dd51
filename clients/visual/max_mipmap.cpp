#include "clients/visual/max_mipmap.hpp"

#include <algorithm>
#include <bit>
#include <limits>

namespace thx::visual {
namespace {

constexpr float kPadding = std::numeric_limits<float>::infinity();

int trailingZeros(int n) { return std::countr_zero(unsigned(n)); }

}  // namespace

float MaxMipmapLevel::bound(int i, int j) const {
  const float* d = &depths[(std::size_t(j) * width + i) * 4];
  return std::min({d[0], d[1], d[2], d[3]});
}

MaxMipmap buildMaxMipmap(const tex::TextureMap& map, const tex::SampleOptions& sampling) {
  MaxMipmap m;
  m.wrap = sampling.address == tex::Address::Wrap;
  m.between_centres = sampling.filter == tex::Filter::Bilinear;
  m.offset = m.between_centres && !m.wrap ? 1 : 0;
  const int w = map.width(), h = map.height();
  m.cells_x = w + m.offset;
  m.cells_y = h + m.offset;
  // Wrapped levels keep whole periods; clamped ones are padded to powers of two.
  const int stored_x = m.wrap ? m.cells_x : int(std::bit_ceil(unsigned(m.cells_x)));
  const int stored_y = m.wrap ? m.cells_y : int(std::bit_ceil(unsigned(m.cells_y)));
  const int top = m.wrap ? std::min(trailingZeros(w), trailingZeros(h))
                         : std::max(trailingZeros(stored_x), trailingZeros(stored_y));

  MaxMipmapLevel base{stored_x, stored_y, std::vector<float>(std::size_t(stored_x) * stored_y * 4, kPadding)};
  const auto depth = [&](int i, int j) {
    return map.depth(tex::resolveIndex(i, w, sampling.address), tex::resolveIndex(j, h, sampling.address));
  };
  for (int j = 0; j < m.cells_y; ++j)
    for (int i = 0; i < m.cells_x; ++i) {
      float* d = &base.depths[(std::size_t(j) * stored_x + i) * 4];
      const int ti = i - m.offset, tj = j - m.offset;  // the cell's first texel centre
      if (m.between_centres) {
        d[0] = depth(ti, tj), d[1] = depth(ti + 1, tj), d[2] = depth(ti, tj + 1), d[3] = depth(ti + 1, tj + 1);
      } else {
        d[0] = d[1] = d[2] = d[3] = depth(ti, tj);
      }
    }
  m.levels.push_back(std::move(base));

  for (int level = 1; level <= top; ++level) {
    const MaxMipmapLevel& fine = m.levels.back();
    MaxMipmapLevel coarse{std::max(1, fine.width / 2), std::max(1, fine.height / 2), {}};
    coarse.depths.assign(std::size_t(coarse.width) * coarse.height * 4, kPadding);
    for (int j = 0; j < coarse.height; ++j)
      for (int i = 0; i < coarse.width; ++i) {
        float v = kPadding;
        for (int dj = 0; dj < 2; ++dj)
          for (int di = 0; di < 2; ++di) {
            const int fi = 2 * i + di, fj = 2 * j + dj;
            if (fi < fine.width && fj < fine.height) v = std::min(v, fine.bound(fi, fj));
          }
        std::fill_n(&coarse.depths[(std::size_t(j) * coarse.width + i) * 4], 4, v);
      }
    m.levels.push_back(std::move(coarse));
  }
  return m;
}

}  // namespace thx::visual
