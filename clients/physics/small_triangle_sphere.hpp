#pragma once
// A ball against a mesh's triangles smaller than Bullet's sphere-triangle test sees.
//
// Bullet meets a sphere with each triangle of a mesh (btConvexConcaveCollisionAlgorithm hands it
// to btSphereTriangleCollisionAlgorithm's SphereTriangleDetector), which skips a triangle whose
// edges' cross product has a squared length under SIMD_EPSILON^2 as degenerate. In the float build
// (`pkg-config bullet`) that is any triangle of less than 0.06 mm^2: a 1 cm ball pressed on a UV
// sphere mesh of 5 mm (128 segments, its faces about 0.25 mm across) met no triangle at all, fell
// through it and was thrown out 1.7 m; on a 1 cm sphere it fell through along the line to a pole,
// where the fan's triangles are thinnest (docs/physics.md, "Small triangles").
//
// This algorithm is Bullet's for every triangle it sees (SphereTriangleDetector, called as
// btSphereTriangleCollisionAlgorithm calls it: the same points to the bit), and for a smaller one
// that is not degenerate (its doubled area over 1e-12 of the square of its longest edge) the triangle's
// own nearest point to the ball's centre (mesh::closestBarycentric, in double): a contact there
// when that point lies within the ball's radius and the breaking threshold, its normal from the
// point to the centre (the face's where the centre lies on the triangle), as Bullet's would give
// for a triangle of the size it is made for. Registered for sphere-triangle pairs by
// registerSmallTriangleSphere; a mesh's own rules then rewrite the points as before
// (mesh_contact.hpp).
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>

namespace thx::phys {

// Whether Bullet's sphere-triangle test sees the triangle (its cross product's squared length
// at least SIMD_EPSILON^2, in btScalar as Bullet computes it).
bool bulletSeesTriangle(const btVector3& a, const btVector3& b, const btVector3& c);

// Replaces Bullet's sphere-triangle algorithm (both orders) on `dispatcher` with the one above.
void registerSmallTriangleSphere(btCollisionDispatcher& dispatcher);

}  // namespace thx::phys
