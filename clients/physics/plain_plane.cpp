#include "clients/physics/plain_plane.hpp"

#include <BulletCollision/BroadphaseCollision/btBroadphaseProxy.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <algorithm>
#include <cmath>

#include "clients/physics/relief_collision.hpp"
#include "clients/physics/textured_ball.hpp"

namespace thx::phys {

namespace {
constexpr int kPlainPlaneTag = 0x74685050;  // "thPP": a plain plane textured objects meet by their texture
}  // namespace

double plainPlaneTexels(const btCollisionShape& object) {
  const FaceTexture* box = faceTextureOf(object);
  const FaceTexture* ball = ballTextureOf(object);
  const FaceTexture* texture = box ? box : ball;
  if (!texture || !texture->map) return 0.0;
  const double texel = texture->tile_m / double(std::max(texture->map->width(), texture->map->height()));
  if (box) {
    btVector3 h = static_cast<const btBoxShape&>(object).getHalfExtentsWithMargin();
    const double a = double(h.x()), b = double(h.y()), c = double(h.z());
    const double longest = std::max({a, b, c}), shortest = std::min({a, b, c});
    const double middle = a + b + c - longest - shortest;
    return (2.0 * longest / texel) * (2.0 * middle / texel);
  }
  // The cap within the pair's breaking threshold of the plane (the plane's own is unbounded), as
  // the raster reads it: a disc of radius sqrt(2 r t), its square of texels.
  const double r = double(static_cast<const btSphereShape&>(object).getRadius());
  const double t = double(object.getContactBreakingThreshold(gContactBreakingThreshold));
  const double side = 2.0 * std::sqrt(2.0 * r * t) / texel;
  return side * side;
}

double plainPlaneTexelBudget(const btCollisionShape& object) {
  return ballTexelGridOf(object) ? kGriddedBallPlainPlaneTexelBudget : kPlainPlaneTexelBudget;
}

void markPlainPlane(btCollisionShape& plane) { plane.setUserIndex(kPlainPlaneTag); }

bool isPlainPlane(const btCollisionShape& shape) {
  return shape.getShapeType() == STATIC_PLANE_PROXYTYPE && shape.getUserIndex() == kPlainPlaneTag;
}

btCollisionAlgorithm* PlainPlaneCreateFunc::CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                                     const btCollisionObjectWrapper* body0,
                                                                     const btCollisionObjectWrapper* body1) {
  const btCollisionObjectWrapper* object = m_swapped ? body1 : body0;
  const btCollisionObjectWrapper* plane = m_swapped ? body0 : body1;
  const btCollisionShape& shape = *object->getCollisionShape();
  if (hasObjectTexture(shape) && isPlainPlane(*plane->getCollisionShape()) &&
      plainPlaneTexels(shape) <= plainPlaneTexelBudget(shape))
    return ManifoldAlgorithm::create<ReliefCollisionAlgorithm>(ci, body0, body1, bool(m_swapped));
  return otherwise->CreateCollisionAlgorithm(ci, body0, body1);
}

std::unique_ptr<PlainPlaneRegistration> registerPlainPlaneCollision(btCollisionDispatcher& dispatcher,
                                                                    btCollisionConfiguration& configuration) {
  auto registration = std::make_unique<PlainPlaneRegistration>();
  for (int type : {BOX_SHAPE_PROXYTYPE, SPHERE_SHAPE_PROXYTYPE}) {
    for (const bool plane_first : {false, true}) {
      const int t0 = plane_first ? int(STATIC_PLANE_PROXYTYPE) : type;
      const int t1 = plane_first ? type : int(STATIC_PLANE_PROXYTYPE);
      registration->funcs.push_back(
          std::make_unique<PlainPlaneCreateFunc>(configuration.getCollisionAlgorithmCreateFunc(t0, t1), plane_first));
      dispatcher.registerCollisionCreateFunc(t0, t1, registration->funcs.back().get());
    }
  }
  return registration;
}

}  // namespace thx::phys
