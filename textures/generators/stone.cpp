// Rough stone: multi-octave gradient noise (relief of a split or bush-hammered face) cut by a few
// cracks along cleft planes.
//
// Relief: `octaves` of gradient noise, the first of wavelength `roughness_wavelength`, each next
// at half the wavelength and `gain` times the amplitude, the sum scaled so its first octave has
// amplitude `roughness`. Octaves shorter than three texels are left out (they would alias).
// Cracks: the borders of a jittered-grid Voronoi network of cell `crack_spacing` (the traces of
// cleft planes on the face), each a raised-cosine groove of width `crack_width` and depth
// `crack_depth` (0 = no cracks). The lattices divide the extent, so the map tiles.
#include "textures/generators/noise.hpp"

namespace thx::tex::gen {

namespace {

constexpr std::uint64_t kStoneSalt = 0x73746f6e;  // "ston"

TextureMap makeStone(const Params& p, int size, std::uint64_t seed) {
  const double extent = p.at("extent"), amplitude = p.at("roughness"), wavelength = p.at("roughness_wavelength");
  const double gain = p.at("gain"), spacing_req = p.at("crack_spacing"), width = p.at("crack_width");
  const double depth = p.at("crack_depth");
  const double octaves_f = p.at("octaves");
  if (octaves_f != std::floor(octaves_f)) {
    failParams("stone", "octaves must be a whole number", "octaves=" + formatNumber(octaves_f), "an integer in [1, 8]");
  }
  // The cells are crack_spacing rounded to divide the extent; a crack must stay under half of that.
  const std::int64_t cells = periodsIn(extent, spacing_req);
  const double cell = extent / double(cells);
  if (width >= cell / 2.0) {
    failParams("stone", "cracks wider than half the crack spacing",
               "crack_width=" + formatNumber(width) + ", crack_spacing=" + formatNumber(spacing_req) + " (used: " +
                   formatNumber(cell) + " = extent/" + std::to_string(cells) + ")",
               "crack_width < the spacing used / 2");
  }
  return rasterizeCrackedNoise(
      size, {.extent = extent, .wavelength = wavelength, .amplitude = amplitude, .gain = gain, .octaves = int(octaves_f),
             .min_wavelength = 3.0 * extent / size, .crack_cell_request = spacing_req, .jitter = 0.9, .crack_width = width,
             .crack_depth = depth, .seed = seed, .salt = kStoneSalt});
}

}  // namespace

GeneratorEntry stoneGenerator() {
  return {{"stone",
           "rough stone: multi-octave gradient noise cut by a few cracks along cleft planes (tiles)",
           {
               {"roughness", 0.0008, "m", "amplitude of the first (longest) noise octave", 0.0, 0.1},
               {"roughness_wavelength", 0.03, "m", "wavelength of the first octave", 1e-3, 100.0},
               {"octaves", 5, "1", "number of octaves, each half the wavelength of the one before", 1, 8},
               {"gain", 0.5, "1", "amplitude ratio of one octave to the one before", 0.1, 0.9},
               {"crack_spacing", 0.06, "m", "typical distance between cracks (grown to divide the extent)", 1e-3,
                100.0},
               {"crack_width", 0.002, "m", "width of a crack", 1e-5, 1.0},
               {"crack_depth", 0.0012, "m", "depth of a crack below the noise; 0 = no cracks", 0.0, 0.1},
           }},
          makeStone};
}

}  // namespace thx::tex::gen
