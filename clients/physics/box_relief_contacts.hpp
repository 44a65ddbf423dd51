#pragma once
// A box's contacts with a relief, chosen as the general rule chooses them (rasterizeRelief, then
// the quarter rule, selectBoxQuarterContacts: relief_raster.hpp, contact_selection.hpp) with a
// fraction of its work. The general rule cost 93.5 µs per step for a 2 cm box on a 1024² relief
// (0.49 mm texels, 41² texels under it), nearly all of it per texel: a ray-slab test with six
// divisions, a decoded normal and an 80-byte candidate for every texel under the box (issue 29).
//
// Here, per texel, only the depth: along a row of texel centres the box's lowest z is the largest
// of its (up to) three lower faces' planes, each affine in x, so two multiply-adds per face; the
// depths go into a grid over the footprint. A level stretch of the relief (one height for at
// least kLevelStretchMin texels) is not read texel by texel: there the depth is convex along the
// row, so the deepest texel lies at the ends of the stretch's touching interval or by where the
// faces' planes cross; and the quarter rule's score (depth less the spread preference, concave
// where one face is lowest) is least at the ends of where one face is lowest, of each quarter's
// part of the stretch and of its part within the tolerance of the deepest. Only those texels are
// read and offered; every touching texel elsewhere is. Normals are read for the chosen texels only.
//
// The same texels as the general rule, except where two texels' scores or depths are equal to
// rounding (then either is the rule's answer), and depths equal to it within rounding (the planes
// are evaluated, not intersected with rays). tests/physics/test_box_relief_contacts.cpp holds the
// two against each other.
#include <array>
#include <cstddef>

#include "clients/physics/contact_selection.hpp"
#include "clients/physics/relief_level_runs.hpp"
#include "clients/physics/relief_raster.hpp"
#include "clients/physics/underside.hpp"
#include "textures/textured_surface.hpp"

namespace thx::phys {

struct ChosenReliefContacts {
  std::array<ReliefCandidate, kMaxReliefContacts> contacts{};  // deepest first, as the rule orders them
  std::size_t count = 0;
  RasterStats raster;
};

// A level stretch at least this long is read at its ends (and where the box's faces cross over
// it); a shorter one texel by texel.
inline constexpr long long kLevelStretchMin = 4;

// The box's (Underside::Kind::Box) contacts, or false where this path does not apply (a footprint
// visited with a stride: the general rule handles it). `surface` reads the map as relief;
// `level_runs`, built from its map, lets level stretches be skipped (nullptr: every texel read).
bool boxReliefContacts(const tex::TexturedSurface& surface, const Underside& box, double threshold_m,
                       ChosenReliefContacts& out, const ReliefLevelRuns* level_runs = nullptr);

// The general rule on the same box (rasterizeRelief, selectBoxQuarterContacts), for tests and
// benchmarks that compare the two.
ChosenReliefContacts generalBoxReliefContacts(const tex::TexturedSurface& surface, const Underside& box,
                                              double threshold_m);

// The quarter rule's bookkeeping for a box (its two axes that lie most in the plane), with its
// tolerance of the deepest depth: the relief's depth step (TextureMap::depthStep).
BoxQuarters quartersUnder(const Underside& box, double depth_tolerance);

}  // namespace thx::phys
