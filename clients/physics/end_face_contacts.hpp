#pragma once
// Contacts of a cylinder standing on an end face on a relief plane (relief_collision.hpp): two
// points on the rim of its lower end face where the face's fall line crosses it, and its deepest
// texel where that lies clearly deeper than both (the face tipped against the relief). A rim point
// clear of the relief (a bumpy relief under the face) goes to the top of the bump nearest it. The
// caller keeps these points between steps, as Bullet keeps its own (its manifold, refreshed).
//
// Why not the deepest and the spread points (contact_selection.hpp), as the other round shapes: on
// a flat face every rim texel is about as deep as every other, so which is the deepest was decided
// by the depths' rounding and by the µm of tilt the step before left, and changed every step; the
// spread points followed it round the rim, chosen afresh each step. The disc rocked and crept
// down slopes its friction holds it on (a 1 cm cylinder, friction 0.3, on a 0.28 slope: up to
// 6.9 mm in 2 s, where Bullet's tilted plane holds it still). Four rim points fixed to the
// cylinder crept too (0.2-0.4 mm in 2 s; kept between steps, up to 0.8 mm): on four points the disc's load is
// statically indeterminate, and it went to one diagonal. Two points on the fall line is Bullet's
// own answer for a disc on a plane; chosen afresh each step they still crept (up to 0.35 mm),
// kept between steps they hold (docs/physics.md, "Relief-map mode").
#include <array>
#include <cstddef>
#include <span>

#include "clients/physics/contact_selection.hpp"
#include "clients/physics/underside.hpp"

namespace thx::phys {

// A cylinder whose axis is within 45° of the plane's normal: it stands on an end face.
bool standsOnEndFace(const Underside& shape);

// How much deeper than both rim points the deepest texel must lie to join them (the face tipped
// against the relief): above the depths' rounding and the ±1 µm a rocking step left (measured).
inline constexpr double kEndFaceTipM = 2e-6;
// A rim point this much shallower than the deepest texel is clear of the relief, and moves to its
// basin. On a slope the rim points stay within a few µm of the deepest (at 2 µm, rocking lifted
// them past it and walking the rounding's basins let a cylinder creep 0.3 mm in 2 s).
inline constexpr double kEndFaceClearM = 10e-6;

// Fills `chosen` with indices into `candidates` (the cylinder's rasterised texels,
// relief_raster.hpp, visited `stride_i` and `stride_j` texels apart); returns how many, at most
// three. `texel_m`: the relief's larger texel side; the rim points are taken that far inside the
// rim, so that the texel nearest each lies under the flat face, not its rounded edge. Deepest
// first (the caller refines the first).
std::size_t selectEndFaceContacts(std::span<const ReliefCandidate> candidates, const Underside& cylinder, double texel_m,
                                  long long stride_i, long long stride_j,
                                  std::array<std::size_t, kMaxReliefContacts>& chosen);

}  // namespace thx::phys
