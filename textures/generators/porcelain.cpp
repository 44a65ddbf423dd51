// Glazed porcelain: nearly flat. A very low, long-wavelength undulation of the glaze (two octaves
// of gradient noise) plus optional crazing, the glaze's thin network of shallow cracks.
//
// The crazing follows the borders of a jittered-grid Voronoi network of cell `craze_cell`: at
// distance s from the nearest border the crack is a raised-cosine groove
//   h = -craze_depth * (1 + cos(pi s / w)) / 2  for s < w = craze_width / 2,
// flat on the crack's centre line and where it meets the glaze; creases only where cracks meet.
// craze_depth = 0 turns the crazing off. The cells divide the extent, so the map tiles.
#include "textures/generators/noise.hpp"

namespace thx::tex::gen {

namespace {

constexpr std::uint64_t kPorcelainSalt = 0x706f7263;  // "porc"

TextureMap makePorcelain(const Params& p, int size, std::uint64_t seed) {
  const double extent = p.at("extent"), amplitude = p.at("undulation"), wavelength = p.at("undulation_wavelength");
  const double cell_req = p.at("craze_cell"), width = p.at("craze_width"), depth = p.at("craze_depth");
  // The cells are craze_cell rounded to divide the extent; a crack must stay under half of that.
  const std::int64_t cells = periodsIn(extent, cell_req);
  const double cell = extent / double(cells);
  if (width >= cell / 2.0) {
    failParams("porcelain", "crazing cracks wider than half a craze cell",
               "craze_width=" + formatNumber(width) + ", craze_cell=" + formatNumber(cell_req) + " (used: " +
                   formatNumber(cell) + " = extent/" + std::to_string(cells) + ")",
               "craze_width < the cell used / 2");
  }
  return rasterizeCrackedNoise(
      size, {.extent = extent, .wavelength = wavelength, .amplitude = amplitude, .gain = 0.5, .octaves = 2,
             .min_wavelength = 3.0 * extent / size, .crack_cell_request = cell_req, .jitter = 0.8, .crack_width = width,
             .crack_depth = depth, .seed = seed, .salt = kPorcelainSalt});
}

}  // namespace

GeneratorEntry porcelainGenerator() {
  return {{"porcelain",
           "glazed porcelain: a faint smooth undulation plus optional crazing (a thin network of shallow cracks)",
           {
               {"undulation", 5e-6, "m", "amplitude of the glaze's smooth undulation", 0.0, 1e-3},
               {"undulation_wavelength", 0.05, "m", "wavelength of the undulation's first octave", 1e-3, 100.0},
               {"craze_cell", 0.008, "m", "typical size of a crazing cell (grown to divide the extent)", 1e-4, 10.0},
               {"craze_width", 0.0006, "m", "width of a crazing crack", 1e-5, 0.1},
               {"craze_depth", 2e-5, "m", "depth of a crazing crack; 0 = no crazing", 0.0, 1e-3},
           }},
          makePorcelain};
}

}  // namespace thx::tex::gen
