#pragma once
// A ball with a bump map on flat ground: its contacts at the lowest points of its own surface.
//
// On flat ground (a plain plane's or a plain box face's smooth chart, or a relief whose depth is
// one level under the ball) the pair's depth is the height of the ball's own recessed surface, so
// its basins are the ball's lowest points, and they move with the ball. The same holds on a
// mesh's chart whose smooth surface bends under the ball (GroundBend: a bowl's or a sphere's),
// smooth or with a relief of one level laid on it: the ground has no features of its own there,
// and each point's gap is measured to the bent ground under it. A smooth relief under the ball
// (reliefSmooth: a dish, a long wave) is read the same way, its height under each point. They are found on the
// ball's texel centres (ball_texel_grid.hpp): the basins of the depth on each cube face's grid
// (no deeper than any of their eight neighbours), chosen as findBallBasins chooses (the four
// closest to closing, then those that can close within the step, up to kMaxBallBasins), each
// refined between the texels by a pattern search in the ball's own texture coordinates, within a
// texel of its centre, to 1/1024 texel. The normal is the ground's.
//
// The texture is read first only where the ball lies within a bound of the ground, from
// the last step's fourth basin (BallBasinHint, as findBallBasins): the recess only lowers the
// surface into the ball, so a texel outside the bound lies above it, and when four basins are
// found under it those are the basins the whole disc within the threshold gives. Otherwise the
// whole disc is read. On flat ground a texel is read where its smooth sphere's point lies within
// the bound (a cap round straight down); on bent ground where its own point does, in the 16 x 16
// blocks that a bound of the smooth sphere over them does not rule out.
//
// Measured on the inside of a smooth 5 cm bowl (a UV sphere mesh), the dimpled ball let down at
// its bottom from 24 starts turned at random, the rest detector on: at the ground's samples 2 of
// 24 rocked at 1.9-2.0 mm/s through the eighth second; on the ball's own texels all 24 slept by
// the third (docs/physics.md, "A ball with a bump map on flat ground").
//
// Sampled at the ground's points instead (findBallBasins, for any ground), a dimple's rim, a sharp
// crest, was read wherever a ground sample fell near it: a dimpled ball let down on a plain plane
// from 36 starts stayed awake in 8, rocking in a dimple at 0.7 mm/s with the rest detector on
// (docs/physics.md, "A ball with a bump map on flat ground").
#include <array>
#include <cstddef>
#include <optional>

#include "clients/physics/ball_texel_grid.hpp"
#include "clients/physics/contact_selection.hpp"
#include "clients/physics/ground_bend.hpp"
#include "clients/physics/textured_ball_basins.hpp"
#include "clients/physics/underside.hpp"
#include "textures/textured_surface.hpp"

namespace thx::phys {

// The ground's height under the ball (plane frame) where it is flat there, for a chart or plane
// with no bend and no edge within reach (the caller knows that): a smooth chart (height 0), or a
// relief whose depth codes are all one over the texels under the ball's touching disc (the part
// of its sphere within `threshold_m` of the ground) and one texel round them. nullopt otherwise,
// and where the ball lies farther than the threshold above the ground.
// On a chart with a bend (`bend`, non-null), the relief's level under the bent ground.
std::optional<double> flatGroundHeight(const tex::TexturedSurface& surface, const Underside& ball, double threshold_m,
                                       const GroundBend* bend = nullptr);

// Whether a relief is smooth over the same texels, its codes not all one: its depth bends by no
// more than kSmoothReliefBend from one texel to the next along a row or a column (the second
// difference of its depth there). Then its bilinear height lies within an eighth of that of a
// smooth surface through its texels, and the ball meets it on its own texels too, that height
// read under each point (ballOnFlatGround's `read_relief`): a dish or a long wave, a nominally
// flat map's quantisation, a uniform slope (a ramp of slope 0.1 tested). Where the relief has
// features of its own (a bumpy plane's 0.4 mm bumps) that reading was worse than the ground's
// samples (docs/physics.md, "A ball with a bump map on flat ground", "Not done"), so the
// tolerance is kept tight: a
// micrometre (the first such reading asked for a relief level to within a micrometre, which
// bends by up to two). On a 10 cm dish of 0.16 mm texels the ball no longer rocks in place, as
// it did at up to 3.9 mm/s from 10 of 60 starts (docs/physics.md, "Smooth reliefs").
inline constexpr double kSmoothReliefBend = 1e-6;
bool reliefSmooth(const tex::TexturedSurface& surface, const Underside& ball, double threshold_m,
                  const GroundBend* bend = nullptr);

// Both questions in one read of the relief's depth codes, which stops as soon as its depth bends
// by more than kSmoothReliefBend: the ground's height where it is flat (`read_relief` false), or
// a smooth relief to be read under each point (`read_relief` true, `height_m` its top over those
// texels); nullopt where it is neither (flatGroundHeight and reliefSmooth ask it).
struct FlatGround {
  double height_m = 0.0;
  bool read_relief = false;
};
std::optional<FlatGround> flatGround(const tex::TexturedSurface& surface, const Underside& ball, double threshold_m,
                                     const GroundBend* bend = nullptr);

// The ball's contacts on flat ground at `ground_z`, deepest first, into `out`; how many. Each
// candidate's p_surface is the ground's point under the ball's point, its depth the gap there
// (negative: into the ground), its normal the ground's (the relief's, sampled there; +z on a
// smooth chart), its texel the ground's. `hint` as findBallBasins reads and updates it.
// With `read_relief` (a smooth relief, reliefSmooth) the ground under a point is the relief's
// bilinear height there, raised by the bend where there is one (`ground_z` then the relief's top
// under the ball, flatGround's height_m, which bounds the blocks read).
// On bent ground (`bend` non-null: a mesh chart's smooth surface, GroundBend), the ground under a
// point lies at ground_z plus the bend's height there, each gap is measured to it and each normal
// is tilted by its slope. nullptr: flat.
std::size_t ballOnFlatGround(const BallTexelGrid& grid, const tex::TexturedSurface& surface,
                             const Underside& ball, double ground_z, const GroundBend* bend, double threshold_m,
                             double closing_within_m, BallBasinHint& hint,
                             std::array<ReliefCandidate, kMaxBallBasins>& out, bool read_relief = false);

}  // namespace thx::phys
