#include "clients/physics/relief_plane_shape.hpp"

#include <BulletCollision/BroadphaseCollision/btBroadphaseProxy.h>
#include <LinearMath/btAabbUtil2.h>

#include <stdexcept>

namespace thx::phys {

ReliefPlaneShape::ReliefPlaneShape(const tex::TexturedSurface& surface)
    : surface_(surface), level_runs_(surface.map()) {
  if (!surface.usesRelief())
    throw std::logic_error("ReliefPlaneShape: the textured surface is not read as a relief map "
                                "(expected a relief map with use_relief = true)");
  m_shapeType = CUSTOM_CONCAVE_SHAPE_TYPE;
}

void ReliefPlaneShape::getAabb(const btTransform& t, btVector3& aabb_min, btVector3& aabb_max) const {
  // The relief lies between the plane (z = 0) and z = -maxDepth in the plane frame.
  const auto lateral = static_cast<btScalar>(kLateralHalfExtent_m);
  const auto depth = static_cast<btScalar>(surface_.map().maxDepth());
  const btVector3 half(lateral, lateral, btScalar(0.5) * depth);
  const btVector3 centre(0, 0, btScalar(-0.5) * depth);
  btTransformAabb(half, getMargin(), btTransform(t.getBasis(), t(centre)), aabb_min, aabb_max);
}

void ReliefPlaneShape::processAllTriangles(btTriangleCallback*, const btVector3&, const btVector3&) const {
  // Deliberately empty: the relief has no triangles (see the header).
}

void ReliefPlaneShape::setLocalScaling(const btVector3& scaling) {
  // Scaling would silently disagree with the texture's own metric mapping: keep it at 1.
  (void)scaling;
}

void ReliefPlaneShape::calculateLocalInertia(btScalar, btVector3& inertia) const { inertia.setValue(0, 0, 0); }

}  // namespace thx::phys
