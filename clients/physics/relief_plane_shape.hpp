#pragma once
// The relief plane as a Bullet shape: a flat plane whose detail (relief depth and normals) lives
// in a texture. Only our own collision algorithms (relief_collision.hpp) look inside it; the
// shape type is CUSTOM_CONCAVE_SHAPE_TYPE so the dispatcher routes any pair we did not register
// to btConvexConcaveCollisionAlgorithm, which finds no triangles here (processAllTriangles is
// empty) and so reports no contact rather than a wrong one.
//
// The shape's frame IS the surface's plane frame: the body carrying it must be placed at the
// surface mapping's plane_to_world (PhysicsWorld::addReliefPlane does).
#include <BulletCollision/CollisionShapes/btConcaveShape.h>

#include "clients/physics/relief_level_runs.hpp"
#include "textures/textured_surface.hpp"

namespace thx::phys {

class ReliefPlaneShape : public btConcaveShape {
 public:
  // Lateral half-size of the bounding box: the texture continues beyond its rectangle (wrap or
  // clamp), so the plane is unbounded in practice; 1 km keeps Bullet's float AABB arithmetic sane.
  static constexpr double kLateralHalfExtent_m = 1000.0;

  // `surface` must read the map as relief (usesRelief()); throws std::logic_error otherwise (a
  // caller's bug: PhysicsWorld::addReliefPlane's callers check usesRelief()).
  explicit ReliefPlaneShape(const tex::TexturedSurface& surface);

  const tex::TexturedSurface& surface() const { return surface_; }
  // Where the relief stays level along its rows (a box's contact search skips those stretches).
  const ReliefLevelRuns& levelRuns() const { return level_runs_; }

  void getAabb(const btTransform& t, btVector3& aabb_min, btVector3& aabb_max) const override;
  void processAllTriangles(btTriangleCallback* callback, const btVector3& aabb_min,
                           const btVector3& aabb_max) const override;
  void setLocalScaling(const btVector3& scaling) override;
  const btVector3& getLocalScaling() const override { return scaling_; }
  void calculateLocalInertia(btScalar mass, btVector3& inertia) const override;
  const char* getName() const override { return "thx::ReliefPlane"; }

 private:
  tex::TexturedSurface surface_;
  ReliefLevelRuns level_runs_;
  btVector3 scaling_{1, 1, 1};
};

}  // namespace thx::phys
