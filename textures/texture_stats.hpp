#pragma once
// Summary statistics of a TextureMap, for `texturetool info` and for reports.
//
// Slope angles are the tilt of the normal from the plane's +z: tilt = acos(n.z). A texel steeper
// than `steep_deg` is one a stylus is likely to catch on, or to slip off, so it is counted.
// Bad texels are not counted here: the loader reports them (LoadReport in texture_io.hpp).
#include <cstddef>
#include <string>

#include "textures/texture_map.hpp"

namespace thx::tex {

struct TextureStats {
  int width = 0;
  int height = 0;
  Representation representation = Representation::Normal;
  int bit_depth = 0;  // of the file it came from; 0 = unknown (the caller fills it in)
  double max_depth_m = 0.0;

  // Depth in metres into the surface (all 0 for normal maps).
  double depth_min_m = 0.0;
  double depth_max_m = 0.0;
  double depth_mean_m = 0.0;

  double mean_nz = 1.0;
  double min_nz = 1.0;             // the steepest texel's n.z
  double steepest_deg = 0.0;       // acos(min_nz)
  double mean_tilt_deg = 0.0;      // mean of acos(n.z)
  double steep_threshold_deg = 60.0;
  std::size_t steep_texels = 0;    // texels with tilt > steep_threshold_deg
  TexelIndex steepest_texel;
};

TextureStats computeStats(const TextureMap& map, double steep_threshold_deg = 60.0);

// Multi-line, human-readable, one "name: value" per line (units in the text).
std::string formatStats(const TextureStats& stats);

}  // namespace thx::tex
