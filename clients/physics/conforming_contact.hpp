#pragma once
// A ball in a relief that conforms to it (a dimple whose cap has the ball's own radius,
// scenes/dimple_ball.yaml): the ball touches every texel of the cap at once, so the vertical
// depths the raster measures are equal to a µm over the whole cap. The usual rule (the deepest
// texel refined on the bilinear surface, spread points snapped to their basins) then measured
// the gap three ways that disagree there (the refined point on a bilinear chord 12-19 µm above
// the cap, rim texels whose normals cross the rim's kink, flat texels outside the rim mapped to
// the ball's bottom) and picked a deepest point that hopped around the cap: the ball rocked in
// a two-step cycle (2.3 mm/s at 1 kHz, 98 mm/s and 1.5 mm deep at 60 Hz).
//
// For such a ball the contacts are chosen by position, not by depth, and measured one way:
// from the texel under the ball's centre, walk along +x, +y, -x, -y while the relief keeps the
// ball's curvature (below); the last texel of each walk is a contact, at the widest ring the
// conforming cap offers (the steepest support: on narrower rings the ball rolled to and fro
// on its four facets at 60 Hz, docs/physics.md "Known gaps"), and its gap is the ball's
// distance from that texel's tangent plane, (c - P)·n - r. A walk stops at the last texel whose
// two neighbours are on the cap, so every contact texel's central-difference normal lies wholly
// on the cap. The four texels depend on the texel under the ball's centre and (near the rim,
// where an off-centre ball's depths curve) on its offset, not on µm motions; when they change
// it is to other texels of the same cap, measured the same way.
#include <array>
#include <vector>

#include "clients/physics/contact_selection.hpp"
#include "clients/physics/underside.hpp"
#include "textures/textured_surface.hpp"

namespace thx::phys {

// The relief keeps the ball's curvature at a texel when the second difference of the vertical
// depth (ball's lowest z minus relief height) over its two neighbours along the walk is below
// this fraction of a flat plane's, t^2 / r (t: texel size). A second difference, not the depths:
// a ball off the cap's centre adds a slope to the depths, not a curvature.
inline constexpr double kConformFraction = 0.25;
// Conforming only when every walk gets this far (texels): a ball near the cap's edge, or on a
// relief that conforms over a smaller patch, keeps the usual rule. So does a ball that touches
// the relief elsewhere than at the ring (a candidate deeper than the ring's deepest texel by
// more than the curvature tolerance t^2 / 4r plus the ring's own penetration): one crossing a
// cap fast, against its far wall.
inline constexpr long long kConformMinWalk = 3;

// Fills `chosen` with the conforming contacts (appended to `candidates`, the rasterised ones,
// deepest first) and returns how many (4), or returns 0 when the relief under the ball (a sphere)
// does not conform to it or it touches elsewhere; `surface` reads the map as relief.
std::size_t selectConformingContacts(const tex::TexturedSurface& surface, const Underside& ball,
                                     std::vector<ReliefCandidate>& candidates,
                                     std::array<std::size_t, kMaxReliefContacts>& chosen);

}  // namespace thx::phys
