#pragma once
// The basins a ball with a bump map's contacts are chosen from (textured_ball.hpp,
// selectShallowestBasins), found without reading the ball's texture over its whole touching disc.
// That read was the ball's cost: under the shipped dimpled ball pushed on a plain plane, its disc
// within Bullet's breaking threshold (0.35 mm for a 1 cm ball) held 5,900-7,100 texels a step,
// each a cube-sphere lookup and a bilinear read, while in four of five steps of the physics tests'
// balls the last basin chosen lay within a tenth of the threshold of the relief.
//
// The texture is read first only where the smooth sphere lies within a bound of the relief
// (rasterizeRelief's `texture_within_m`): as far above the ball's lowest point as its fourth basin
// lay at the last step, and a little more, and no less than the gap kept past the fourth. A relief
// only recesses the sphere, so every texel left out lies deeper than the bound. When four basins
// are found and the fourth lies above the bound, those are the basins the whole disc gives, to
// the bit, and so are the further ones below the bound: every texel left out lies deeper than
// each of them, so it neither is chosen before them nor, as a neighbour, unmakes one (a missing
// neighbour and a deeper one count alike), and the texels read are read as the whole disc reads
// them, in the same order. Otherwise the whole disc is read. What the last step left only decides
// how much is read, never what is found.
#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <vector>

#include "clients/physics/chart_boundary.hpp"
#include "clients/physics/contact_selection.hpp"
#include "clients/physics/ground_bend.hpp"
#include "clients/physics/relief_raster.hpp"
#include "clients/physics/textured_box.hpp"
#include "clients/physics/underside.hpp"
#include "textures/textured_surface.hpp"

namespace thx::phys {

// What a ball's last basins tell the next search: how far above the ball's lowest point (its
// centre's height less its radius and the bend's under the centre) the fourth lay; NaN: unknown
// (fewer than four, or no step yet), the whole disc is read.
struct BallBasinHint {
  double reach_m = std::numeric_limits<double>::quiet_NaN();
};

// The bound read first: the hint's reach times kBallBasinReachGrowth, plus kBallBasinReachMargin of
// the threshold (2.7 µm for a 1 cm ball). A ball at rest keeps its reach to the nanometre; a
// rolling one's changes by more than any margin that still saves reading (a bumpy ball's fourth
// tip moves out and in as it rolls), and its search then reads the whole disc after the bound.
// Chosen on bench_pen_on_objects and bench_textured_ball (docs/physics.md, "A ball with a bump
// map", Cost): with growth 1.5 and margin 1/32 a resting dimpled ball's step cost a third more
// (the bound 0.20 against 0.14 mm above its lowest point in a dimple, its rim 0.13 mm up), a
// rolling bumpy ball's the same.
inline constexpr double kBallBasinReachGrowth = 1.1, kBallBasinReachMargin = 1.0 / 128.0;
// That bound, for a ball whose lowest point stands `lowest_gap` above the ground (meaningful where
// the hint's reach is finite): no less than `closing_within_m`, the gap basins past the fourth are
// kept within.
inline double firstReadBound(const BallBasinHint& hint, double lowest_gap, double threshold_m, double closing_within_m) {
  return std::max(lowest_gap + kBallBasinReachGrowth * std::max(0.0, hint.reach_m) + kBallBasinReachMargin * threshold_m,
                  closing_within_m);
}

// How many basins a ball keeps as contacts: the four closest to closing, and after them those
// that can close within the step (`closing_within_m`, closableGap), up to kMaxBallBasins. Four
// alone left a dimpled ball rocking on a flat relief from a third to two fifths of 36 starts, on
// rims of its dimples that were not yet contacts when they closed; with these, from a tenth to a
// quarter (docs/physics.md, "Known gaps"). No more than twelve lay within the threshold there at
// 0.31 mm texels.
inline constexpr std::size_t kMaxBallBasins = 12;

struct BallBasins {
  std::size_t count = 0;                             // basins chosen, at most kMaxBallBasins
  std::array<std::size_t, kMaxBallBasins> picked{};  // into the candidates, deepest first
  RasterStats raster;                                // the last read's
  bool whole_disc = false;                           // the last read was the whole disc's
  int passes = 0;                                    // reads: 1, or 2 where the bound fell short
};

// `candidates` is cleared and left holding the last read's candidates (past `boundary` dropped),
// which `picked` indexes. `closing_within_m`: the depth (gap) below which basins past the fourth
// are kept. The rest as rasterizeRelief, without normals (`normals` false: withNormals reads them
// for the basins kept). `hint` is read and updated for the next step.
BallBasins findBallBasins(const tex::TexturedSurface& surface, const Underside& ball, const FaceTexture& texture,
                          double threshold_m, double closing_within_m, const GroundBend* bend,
                          const ChartBoundary* boundary, BallBasinHint& hint, std::vector<ReliefCandidate>& candidates);

}  // namespace thx::phys
