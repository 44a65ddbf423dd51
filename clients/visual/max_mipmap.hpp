#pragma once
// The relief's max-mipmap (a quadtree of the highest surface point, i.e. the MINIMUM depth, per
// square of cells): what lets the accelerated relief search (`--search maxmip`) skip empty space
// without ever stepping over a thin wall. A cell of the surface the senses share is, with
// bilinear sampling, the square between four texel centres (the bilinear patch never rises above
// its highest corner) and, with nearest sampling, a texel (flat-topped). Level 0 holds each
// cell's four corner depths (the exact patch, one fetch; its bound is their minimum); level L
// holds the minimum over 2^L x 2^L level-0 cells (in all four channels). Built at load, linear in
// texels (docs/visual.md has the measured time); no cache file.
//
// Indexing (what the shader does): a point's cell coordinates are m = (s, t) + offset on the grid
// of texel centres (textures/sampling.hpp texelS/texelT) for bilinear sampling, or s + 0.5,
// t + 0.5 (texel coordinates) for nearest; the level-L box holding m is K = floor(m / 2^L).
// Wrap: K modulo the level's size (the levels stop where 2^L no longer divides both sides, so the
// period is whole). Clamp: K clamped to the level's real cells. Clamped and bilinear, level 0 has
// a ring of cells between the edge centres and the map's border (offset 1), whose patches are
// constant across the border, so the clamped cell is exact for any point beyond it.
#include <vector>

#include "textures/sampling.hpp"
#include "textures/texture_map.hpp"

namespace thx::visual {

struct MaxMipmapLevel {
  int width = 0, height = 0;   // stored size (GL's mip chain: max(1, level-0 size >> L))
  // Metres, 4 per cell, row-major, row 0 = the map's top. Level 0: the depths at the cell's
  // corners (i, j), (i+1, j), (i, j+1), (i+1, j+1); above: the minimum, 4 times; +inf in padding.
  std::vector<float> depths;
  float bound(int i, int j) const;  // the highest point: the minimum of the four

};

struct MaxMipmap {
  bool wrap = true;
  bool between_centres = true;  // bilinear: cells between texel centres; nearest: texels
  int offset = 0;               // added to texel-centre coordinates (see above)
  int cells_x = 0, cells_y = 0;  // real level-0 cells
  std::vector<MaxMipmapLevel> levels;  // levels[0] finest; levels.back() the coarsest
  int topLevel() const { return int(levels.size()) - 1; }
};

MaxMipmap buildMaxMipmap(const tex::TextureMap& map, const tex::SampleOptions& sampling);

}  // namespace thx::visual
