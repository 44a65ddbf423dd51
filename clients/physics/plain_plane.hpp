#pragma once
// A plain plane (PhysicsWorld::addPlainPlane: a btStaticPlaneShape with no texture of its own) as a
// textured object meets it (issue 29): a textured box or a ball with a bump map meets it on a
// smooth chart laid under it, flat, sampled at the object's own texels, as it meets a plain box's
// face (box_ground.hpp), so that its texture shapes the contact (relief_collision.cpp). Every other
// object keeps Bullet's convex-plane points. A normal-mapped plane is a btStaticPlaneShape too but
// is not marked: its textured objects meet the relief its normals integrate to
// (PhysicsWorld::addTexturedObjectsRelief).
//
// Only where that is affordable: a flat face on flat ground is within reach everywhere, and the
// raster reads the object's texture at every one of its texels there (the 2 x 2 cm grooved block,
// 4,096 texels of 0.31 mm: 0.59 ms a step, bench_pen_on_objects). An object whose underside would hold
// more than kPlainPlaneTexelBudget of its texels (a box's two longer sides; a ball's cap within
// its contact breaking threshold of the plane) meets a plain plane as its coarse shape: the
// 20 x 20 cm slab of the tests, 410,000 texels (512 x 512 samples), cost 12.8 ms a step read so.
// A ball with its texel grid (GriddedBallTexture, as PhysicsWorld::addTexturedSphere lays it)
// meets a plain plane on its own texels instead (ball_on_flat_ground.hpp), and is held to
// kGriddedBallPlainPlaneTexelBudget of the same count, eight times the raster's: the 1 cm dimpled
// ball rolling on the plane at 0.1 m/s cost 110-120 us a step at 256 texels a face (7,361 by that
// count) against 644-659 us read by the raster, and 185, 254, 514 and 841 us at 384, 512, 768 and
// 1024 texels a face (16,562 to 117,772), where at 384 and more it had met the plane as a smooth
// sphere; the raster at its own budget, at its 88 ns a texel, about 1.4 ms (docs/physics.md, "A
// textured object on a plain plane").
#include <BulletCollision/CollisionDispatch/btCollisionConfiguration.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionShapes/btCollisionShape.h>

#include <memory>
#include <vector>

namespace thx::phys {

inline constexpr double kPlainPlaneTexelBudget = 16384.0;
inline constexpr double kGriddedBallPlainPlaneTexelBudget = 131072.0;

// How many of its own texels a textured object's underside holds on a plain plane (above); 0 for
// an object without a texture.
double plainPlaneTexels(const btCollisionShape& object);
// The most of them it may hold and still meet a plain plane by its texture: the gridded ball's
// budget for a ball with a texel grid, the raster's for the rest.
double plainPlaneTexelBudget(const btCollisionShape& object);

// Marks a btStaticPlaneShape as a plain plane that textured objects meet by their texture.
void markPlainPlane(btCollisionShape& plane);
// Whether the shape is a plane so marked.
bool isPlainPlane(const btCollisionShape& shape);

// The create function for a box or a sphere against a static plane: the relief algorithm
// (relief_collision.hpp) where the object carries a texture within its budget and the plane is a
// marked plain plane, `otherwise` (the configuration's convex-plane algorithm) for the rest.
struct PlainPlaneCreateFunc : btCollisionAlgorithmCreateFunc {
  PlainPlaneCreateFunc(btCollisionAlgorithmCreateFunc* otherwise_func, bool plane_first)
      : otherwise(otherwise_func) {
    m_swapped = plane_first;
  }
  btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                 const btCollisionObjectWrapper* body0,
                                                 const btCollisionObjectWrapper* body1) override;
  btCollisionAlgorithmCreateFunc* otherwise;
};

// The create functions of one dispatcher (they point at its configuration's); must outlive its use.
struct PlainPlaneRegistration {
  std::vector<std::unique_ptr<PlainPlaneCreateFunc>> funcs;
};

// Registers PlainPlaneCreateFunc for box and sphere against a static plane, in both orders.
std::unique_ptr<PlainPlaneRegistration> registerPlainPlaneCollision(btCollisionDispatcher& dispatcher,
                                                                    btCollisionConfiguration& configuration);

}  // namespace thx::phys
