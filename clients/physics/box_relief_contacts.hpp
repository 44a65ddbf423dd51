#pragma once
// A box's contacts with a relief, chosen as the general rule chooses them (rasterizeRelief, then
// selectReliefContacts and snapToBasins: relief_raster.hpp, contact_selection.hpp) with a
// fraction of its work. The general rule cost 93.5 µs per step for a 2 cm box on a 1024² relief
// (0.49 mm texels, 41² texels under it), nearly all of it per texel: a ray-slab test with six
// divisions, a decoded normal and an 80-byte candidate for every texel under the box, three
// selection passes over all of them and a basin grid built from them (issue 29).
//
// Here, per texel, only the depth: along a row of texel centres the box's lowest z is the largest
// of its (up to) three lower faces' planes, each affine in x, so two multiply-adds per face; the
// depths go into a grid over the footprint. The deepest texel is tracked while rasterising; the
// spread points (farthest from the deepest, from the line, most area) maximise scores that are
// convex along a row (a distance, the absolute value of an affine function, the largest of three
// such), so each row's run of touching texels can only score its best at one of its two ends:
// only the runs' ends are scored. The basin walk reads the depth grid, and is not walked where
// every walk provably ends at the deepest texel (a box on one level of the relief with one face
// lowest: its depth is a plane there, whose walks' ends are found row by row); normals are read
// for the chosen texels only.
//
// The same texels as the general rule, except where two texels' scores or depths are equal to
// rounding (then either is the rule's answer: a level box on a level relief has every texel
// equally deep), and depths equal to it within rounding (the planes are evaluated, not
// intersected with rays). tests/physics/test_box_relief_contacts.cpp holds the two against each
// other.
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
  // The basin walks were not walked: every one was known to end at the deepest texel (a box on
  // one level of the relief with one face lowest, box_relief_contacts.cpp's oneBasin).
  bool one_basin = false;
};

// A level stretch at least this long is read at its ends (and where the box's faces cross over
// it); a shorter one texel by texel.
inline constexpr long long kLevelStretchMin = 4;

// The box's (Underside::Kind::Box) contacts, or false where this path does not apply (a footprint
// visited with a stride: the general rule handles it). `surface` reads the map as relief;
// `level_runs`, built from its map, lets level stretches be skipped (nullptr: every texel read).
bool boxReliefContacts(const tex::TexturedSurface& surface, const Underside& box, double threshold_m,
                       ChosenReliefContacts& out, const ReliefLevelRuns* level_runs = nullptr);

// The general rule on the same box (rasterizeRelief, selectReliefContacts, snapToBasins), for
// tests and benchmarks that compare the two.
ChosenReliefContacts generalBoxReliefContacts(const tex::TexturedSurface& surface, const Underside& box,
                                              double threshold_m);

}  // namespace thx::phys
