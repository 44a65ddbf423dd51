#pragma once
// Which normal a contact between a relief plane and a textured object takes (issue 29, two textured
// bodies; textured_box.hpp, textured_ball.hpp). The rasteriser gives every texel the mean of the two surfaces'
// normals: right where the two touch wall on wall (they agree there), half wrong where a crest of
// one presses on a wall of the other. There the wall sets the normal, as a vertex touching a face
// takes the face's in Bullet and as a plain box's face on a crease of the relief does
// (crease_contact.hpp). Measured on the grooved block (V-grooves 4 mm apart, walls at 26.6°,
// friction 0.3; bench_textured_pair, the force raised over 0.5 s): the force that pushes it
// across its grooves rose from 0.79, 0.87 and 0.79 of its weight (64, 128 and 256 texels) to
// 0.91, 0.92 and 0.93, against the wedge's 0.941 (docs/physics.md, "Textured objects").
#include <span>

#include "clients/physics/contact_selection.hpp"
#include "clients/physics/ground_bend.hpp"
#include "clients/physics/textured_object_surface.hpp"
#include "textures/textured_surface.hpp"

namespace thx::phys {

// For each contact (a texel centre of the plane, as the rasteriser made it): how sharply each
// surface bends there, its heights' second difference over the texel and its neighbours (along a
// row and along a column, the larger, over the texel's size: the slope's jump across it). Where
// exactly one of the two jumps by more than kCreaseSlopeJump (crease_contact.hpp) the contact
// takes the other's normal. Where neither does (smooth bumps, wall on wall) or both do (a brick's
// edge on a rounded groove's rim: neither is the face), it keeps the mean: taking the less bent
// one's there too, the grooved block pushed over the bowl's bricks was thrown at 0.096 m/s
// (0.048 with the mean). The plane is read centred; the object, on its footprint's rim, one texel
// in. `bend`: the chart's bent ground on a mesh, nullptr on a plane.
void smootherSurfaceNormals(const tex::TexturedSurface& surface, const GroundBend* bend, const TexturedObjectSurface& object,
                            std::span<ReliefCandidate> contacts);

// A ball with a bump map's contacts (textured_ball.hpp) where the relief round them is much
// flatter than the ball: the relief's own normal. The two surfaces' slopes agree where the pair's
// depth is least, at g_plane + H_plane d (each surface a quadratic round the contact: its slope g
// from its normal, its Hessian H from its heights over the 3 x 3 texels round it; d the minimum's
// offset, -(H_object - H_plane)^-1 (g_object - g_plane)); where |H_plane| is at most
// kFlatterRelief times |H_object| that is the relief's slope within about a tenth of the two slopes'
// difference, where the rasteriser's mean is off by half of it. The mean leans by half the ball's
// slope at the texel centre, off the true point by up to half a texel: four such points under a
// bumpy ball on a flat relief, leaning up to 0.005 rad each way, kept it cycling at 0.3 mm/s;
// with the relief's normal it falls asleep. The full expression above, used everywhere the pair's
// depth curves up, made a bumpy ball on a bumpy relief (tip on tip) worse (3-5 mm/s against
// 0.9; the ball's Hessian read from its bilinear relief is noisy at the texels' scale): not kept.
inline constexpr double kFlatterRelief = 0.1;
void flatterReliefNormals(const tex::TexturedSurface& surface, const GroundBend* bend, const TexturedObjectSurface& object,
                          std::span<ReliefCandidate> contacts);

}  // namespace thx::phys
