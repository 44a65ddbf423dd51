// Ceramic tiles: square tiles on a square grid (joints at x, y = k * tile from the corner),
// separated by flat-bottomed grout lines, each tile's edge rounded down into the grout by a bevel,
// faces almost flat (a faint gradient-noise undulation of the glaze).
//
// Across one axis, with d = distance from the point to the tile's edge line (the joint's centre
// line) and g = grout / 2, the edge profile is
//   B(d) = 0 (grout) for d < g,  (1 - cos(pi (d - g) / bevel)) / 2 (bevel) up to g + bevel,  1 (face),
// and the tile is the product of the two axes' profiles,
//   h = -grout_depth * (1 - B(d_x) B(d_y))   plus the undulation everywhere,
// so the grout is flat at -grout_depth, the face at 0, the bevel has zero slope where it meets
// both, and the corners are rounded without a crease (a min of the two distances would crease
// along the corner diagonals). The tiles divide the extent, so the map tiles.
#include "textures/generators/noise.hpp"

namespace thx::tex::gen {

namespace {

constexpr std::uint64_t kTileSalt = 0x74696c65;  // "tile"

// The edge profile across one axis: 0 in the grout, rising along a half cosine over the bevel,
// 1 on the face; db = its derivative along the distance from the edge line.
struct Rise {
  double b, db;
};
Rise rise(double d, double g, double bevel) {
  if (d < g) return {0.0, 0.0};
  if (d >= g + bevel) return {1.0, 0.0};
  const double t = kPi * (d - g) / bevel;
  return {0.5 * (1.0 - std::cos(t)), 0.5 * kPi / bevel * std::sin(t)};
}

TextureMap makeCeramicTile(const Params& p, int size, std::uint64_t seed) {
  const double extent = p.at("extent"), tile_req = p.at("tile"), grout = p.at("grout");
  const double grout_depth = p.at("grout_depth"), bevel = p.at("bevel"), undulation = p.at("undulation");
  if (grout + 2.0 * bevel >= tile_req) {
    failParams("ceramic_tile", "grout and bevels leave no flat face",
               "tile=" + formatNumber(tile_req) + ", grout=" + formatNumber(grout) + ", bevel=" + formatNumber(bevel),
               "grout + 2 * bevel < tile");
  }
  const std::int64_t n = periodsIn(extent, tile_req);
  const double tile = extent / double(n), g = grout / 2.0, texel = extent / size;
  const FractalNoise glaze(extent, tile, 2, undulation, 0.5, 3.0 * texel, seed, kTileSalt);
  return rasterize(size, extent, [&](double x, double y) {
    SurfacePoint s = glaze(x, y);
    const double u = x - (std::floor(x / tile) + 0.5) * tile, v = y - (std::floor(y / tile) + 0.5) * tile;
    // Distances to the tile's edge lines across x and y; each shrinks away from the tile's centre.
    const Rise bx = rise(tile / 2.0 - std::fabs(u), g, bevel), by = rise(tile / 2.0 - std::fabs(v), g, bevel);
    s.h -= grout_depth * (1.0 - bx.b * by.b);
    s.dhdx += grout_depth * bx.db * by.b * (u > 0.0 ? -1.0 : 1.0);
    s.dhdy += grout_depth * bx.b * by.db * (v > 0.0 ? -1.0 : 1.0);
    return s;
  });
}

}  // namespace

GeneratorEntry ceramicTileGenerator() {
  return {{"ceramic_tile",
           "square glazed tiles with beveled edges and flat-bottomed grout lines; faces almost flat",
           {
               {"tile", 0.05, "m", "tile pitch, grout included (grown or shrunk to divide the extent)", 1e-3, 10.0},
               {"grout", 0.003, "m", "grout line width", 1e-5, 1.0},
               {"grout_depth", 0.0008, "m", "depth of the grout below the tile face", 1e-6, 0.1},
               {"bevel", 0.0015, "m", "width of the rounded edge from face down to grout", 1e-5, 1.0},
               {"undulation", 4e-6, "m", "amplitude of the faint undulation of the glaze", 0.0, 1e-3},
           }},
          makeCeramicTile};
}

}  // namespace thx::tex::gen
