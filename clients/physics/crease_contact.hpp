#pragma once
// A box's face resting on a crease of the relief (a step's top edge, a ridge) is pushed along the
// face's normal, not the relief's (issue 29). A relief's normal at a texel is its heights'
// central differences: at a brick's top edge beside a 0.6 mm joint it leans 31° towards the
// joint, and a 2 cm box resting flat on 12 x 6 mm bricks, square to the texels, was pushed about
// by those contacts for good (0.44-0.73 mm in 2 s at up to 8 mm/s, the rest detector on or off).
// Where the box touches with the inside of one flat face, that face is the smooth surface of the
// two and its normal is the contact's.
#include "clients/physics/box_relief_contacts.hpp"
#include "clients/physics/underside.hpp"
#include "textures/textured_surface.hpp"

namespace thx::phys {

// Where the relief's slope jumps by more than this across a texel (its one-sided differences
// along a row or a column) it has a crease there. Smooth bumps (the pebbles) stay below it and
// keep their own normals.
inline constexpr double kCreaseSlopeJump = 0.3;

// For each of a box's chosen contacts: the normal of the box's face instead of the relief's where
// - the vertical lines through the texel and its 8 neighbours that meet the box enter it by one
//   lower face (the box is flat around the contact: not its edge or corner);
// - the relief has a convex crease at the texel (its height above both neighbours' mean, along
//   a row or a column, by more than kCreaseSlopeJump times the texel).
// A box driven against a kerb is still held back by the floor's texels beside the kerb, whose
// normals lean away from it (concave there, not a crease): BoxOnAReliefCrease.*.
void faceNormalsOnCreases(const tex::TexturedSurface& surface, const Underside& box, ChosenReliefContacts& chosen);

}  // namespace thx::phys
