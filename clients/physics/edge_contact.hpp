#pragma once
// A rod lying over a mesh's convex edge (a box's top edge, a slab's) is pushed along its own
// normal there, not the chart's (issue 29). The chart under a rod tipping over the edge holds its
// contact at the edge's last texels with the face's normal (straight up on a box's top), so
// friction held the rod's side on the edge as on a hinge: a cylinder lying across the grooved
// box's top, its middle 2 mm past the edge, swung under it and left moving back towards the box
// where off a plain box it slides off outwards. Where the rod's side touches the edge, the rod's
// surface is the smooth one of the two and its normal is the contact's, as a box's face on a
// crease of the relief takes the face's (crease_contact.hpp) and as Bullet's own edge contacts do.
#include "clients/physics/box_relief_contacts.hpp"
#include "clients/physics/chart_boundary.hpp"
#include "clients/physics/underside.hpp"

namespace thx::phys {

// For each of a capsule's or a cylinder's chosen contacts within `band_m` of a convex edge of the
// chart (inside it): the rod's normal there (from the contact's surface point square to the axis
// towards it; for a cylinder only along its side, not past its end faces) where it leans out over
// the edge, between the chart's normal and the face's across it. Plane (chart) frame.
void rodNormalsAtConvexEdges(const Underside& rod, const ChartBoundary& boundary, double band_m,
                             ChosenReliefContacts& chosen);

}  // namespace thx::phys
