#pragma once
// Room in a kept manifold for every point chosen this step.
//
// A collision algorithm that keeps its points between steps (a textured box's groups) adds this
// step's chosen points to a manifold that may hold four of earlier steps. Bullet replaces a kept
// point within the breaking threshold of a new one; a new point that meets none, in a full
// manifold, evicts the point whose loss leaves the largest area by Bullet's estimate
// (btPersistentManifold::sortCachedPoints), which may be a point chosen this very step. A grooved
// block resting in grooves chose its four corners; the fourth corner's texel had moved to the
// other end of its row, Bullet's estimate evicted the first corner, just refreshed, and kept a
// stale point beside another: the block fell 13 µm onto that side.
//
// Rule: before the points are added, the kept points that none of them will replace are evicted,
// as many as the new points need, each the kept point nearest a new point that meets none (the
// texel it stood for moved on). Kept points no new point needs stay.
//
// Used for a textured box's level points on flat ground, chosen by quarters (relief_collision.cpp):
// there it held a textured box sliding on a tilted map within 0.01 µm of its height (13 µm with
// the quarters alone). With the spread rule, or applied to every group, it did harm
// (docs/physics.md, "Textured objects", "Kept between steps").
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <span>

namespace thx::phys {

// `on_object`: the world points on the manifold's first body (Bullet's pointA) to be added next,
// in the order they will be added, each within the breaking threshold and none within it of
// another.
void makeRoomFor(btPersistentManifold& manifold, std::span<const btVector3> on_object);

}  // namespace thx::phys
