#pragma once
// Rasterising an object's underside against a relief map over the object's footprint texels only
// (docs/design.md §4 rule 8): for every texel centre under the object's plane-frame bounding box,
// the directional penetration depth along the plane normal, d = (object's lowest z there) - (relief
// height there). Texels where d < threshold become contact candidates.
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "clients/physics/contact_selection.hpp"
#include "clients/physics/ground_bend.hpp"
#include "clients/physics/textured_object_surface.hpp"
#include "clients/physics/underside.hpp"
#include "textures/textured_surface.hpp"

namespace thx::phys {

struct ChartBoundary;  // chart_boundary.hpp

// A footprint wider than this many texels (in total) is visited with a stride, so a huge object
// or a grossly mis-scaled texture costs bounded time; at 1 mm texels that is a 0.5 m object.
inline constexpr long long kMaxFootprintTexels = 512LL * 512LL;

struct RasterStats {
  long long texels_visited = 0;
  long long stride_i = 1, stride_j = 1;  // texels between the ones visited, along i and j
};

// The texels an object's footprint covers (unwrapped indices, inclusive), with the stride that
// bounds their number; `empty` when the object is too high to touch the relief at all. Every
// rasteriser starts from it, so they all visit the same texels.
struct FootprintTexels {
  bool empty = true;
  long long i0 = 0, i1 = -1, j0 = 0, j1 = -1;
  long long stride_i = 1, stride_j = 1;
};
FootprintTexels footprintTexels(const tex::TexturedSurface& surface, const Underside& shape, double threshold_m);

// Appends candidates to `out` (not cleared). `surface` must read the map as relief. A box whose
// faces carry a relief or a ball with a bump map (`object_texture`, textured_box.hpp,
// textured_ball.hpp): the object's surface over each texel is its lowest surface pushed inwards by
// its relief depth there (along the vertical; a point on a box's face steeper than
// kSteepestTexturedFaceCos reads the face turned most towards the plane: faceTextureAt;
// TexturedObjectSurface), and the candidate's normal is the mean of the plane's and the object's
// (turned to face the plane's way; the chosen contacts' normals are then revisited:
// pair_contact_normal.hpp). With `bend` (ground_bend.hpp: a chart on a curved mesh), the relief stands
// on the bent ground: its heights raised by the bend's, its normals tilted by its slope; a chart
// whose texels are twice as long along one axis as along the other is read at the longer spacing
// along both (a texture squeezed by the mesh's uv, relief_raster.cpp).
// `normals` false: the candidates carry their point and depth only (their normal NaN), and
// withNormals reads the relief's and the object's for the ones kept (a plain ball or a ball with a
// bump map reads thousands of texels under it and keeps at most four: on 39 um texels the relief's
// normals took a third of the ridges test's run, by perf). With it true, every candidate carries the relief's
// normal, and a textured object's is read only at the texels that are candidates, their depth read
// first (TexturedObjectSurface::zOver, a box's row by row: textured_box_rows.hpp; a grooved block's
// groove floors lie beyond the threshold).
// `boundary` (a mesh's chart, chart_boundary.hpp): the texels past its edges are not visited; the
// candidates are those that ChartBoundary::past would keep, to the bit (a row's texels are
// visited only between where its edges cut it, a texel wider on either side, and each texel
// within a texel of a cut, or on a row an edge runs nearly along, is tested as past() tests a
// candidate's point). A ball's footprint's rows are likewise visited
// only where its touching disc (footprintTexels) covers them. On a small ball's cube-sphere as
// the ground, the charts across its "creases" (faces 60 degrees round its curvature) held 140,000
// of the ball's texels, most of them past an edge (2026-12-05).
// `texture_within_m` (a ball with a bump map, below threshold_m): its texture is read only where
// its smooth sphere lies within that of the relief, and its touching disc is the one that bound
// gives. A relief only recesses the sphere, so every texel left out stands farther off than the
// bound (textured_ball_basins.hpp says when that leaves the basins chosen the same).
RasterStats rasterizeRelief(const tex::TexturedSurface& surface, const Underside& shape, double threshold_m,
                            std::vector<ReliefCandidate>& out, const FaceTexture* object_texture = nullptr,
                            const GroundBend* bend = nullptr, bool normals = true,
                            const ChartBoundary* boundary = nullptr,
                            double texture_within_m = std::numeric_limits<double>::infinity());
// A candidate rasterised without normals, with them: as rasterizeRelief with `normals` makes it,
// to the bit, given the same surface, bend and object (nullptr: a plain object).
void withNormals(const tex::TexturedSurface& surface, const GroundBend* bend, const TexturedObjectSurface* object,
                 ReliefCandidate& c);
// Whether a candidate carries its normal (rasterised with `normals`, or given them by withNormals).
inline bool hasNormal(const ReliefCandidate& c) { return !std::isnan(c.n_local.x()); }

// Sub-texel refinement of a round object's deepest contact. The texel-centre minimum is off the
// true tangent point by up to half a texel, and its normal with it: at a dimple's bottom the
// deepest of four equal texels pushes the ball sideways, the next step another one pushes it
// back (measured: 0.4 mm/s jitter). A parabola through the depths of the texel and its four
// neighbours locates the minimum within the texel; the relief is then sampled there bilinearly
// (the project's one sampling convention) for its height and normal. With `bend`, on the bent
// ground as rasterizeRelief reads it. With `object_texture` (a ball with a bump map), the pair's
// depth, as rasterizeRelief reads it, and the mean of the two surfaces' normals there; where its
// point lies near the texel's border, the parabolas are fitted again through it until it settles,
// so that the two texels either side of a basin's bottom give one point; with
// `settle_everywhere`, every point (on samples much coarser than the ball's texels one parabola
// through three puts a bump tip's point micrometres off, on a side that changes as they move).
ReliefCandidate refineDeepest(const tex::TexturedSurface& surface, const Underside& shape, const ReliefCandidate& c,
                              const GroundBend* bend = nullptr, const FaceTexture* object_texture = nullptr,
                              bool settle_everywhere = false);

// A plain ball over a relief none of whose texel centres lies within the threshold of its sphere:
// on texels coarse against the ball it still touches the relief between them (a 5 mm ball whose
// lowest point lies between four 1.95 mm texels' centres stands 0.19 mm over them while it touches
// the flat relief; with no contact it fell in and rattled there, docs/physics.md "Relief texels
// coarse against a ball"). The point of the relief (bilinear, raised by `bend`) nearest the
// sphere along the plane's normal, found from under the ball's centre by parabolas along each
// axis, every move one that brings the two closer, through points ever closer; nullopt where that
// point lies farther than `threshold_m`. Its texel is the one it lies in; its normal the relief's.
std::optional<ReliefCandidate> deepestBetweenTexelCentres(const tex::TexturedSurface& surface, const Underside& ball,
                                                          const GroundBend* bend, double threshold_m);

// A box over a relief none of whose texel centres lies within the threshold under it, or too few
// to stand on (boxUnderTwoTexelsAcross; one centre by a corner left an 8 mm box 2.7 mm low on
// 7.81 mm texels, and an 8 mm box whose footprint held no centre of 12.5 mm texels had no contact
// and fell through the relief): its four lowest corners, each a contact where it lies within
// `threshold_m` of the relief (bilinear, raised by `bend`) straight under it, its normal the
// relief's there; and of the texel centres' contacts `centres`, those more than 1 um deeper than
// every corner (a bump under the box), each in place of the shallowest corner once four are kept.
// Returns how many, at most four, into `out`.
std::size_t boxCornerContacts(const tex::TexturedSurface& surface, const Underside& box, const GroundBend* bend,
                              double threshold_m, std::span<const ReliefCandidate> centres,
                              std::array<ReliefCandidate, kMaxReliefContacts>& out);
// Whether the box's footprint (its extent in the plane) is less than two texels across along
// either of the map's axes: too few texel centres under it to stand on.
bool boxUnderTwoTexelsAcross(const tex::TexturedSurface& surface, const Underside& box);

}  // namespace thx::phys
