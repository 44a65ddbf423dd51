#include "clients/physics/small_triangle_sphere.hpp"

#include <BulletCollision/CollisionDispatch/SphereTriangleDetector.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/CollisionShapes/btTriangleShape.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "clients/physics/bullet_convert.hpp"
#include "clients/physics/manifold_algorithm.hpp"
#include "meshes/textured_mesh.hpp"

namespace thx::phys {

namespace {

// A triangle whose doubled area is under this fraction of its longest edge's square is a needle or
// a point: no normal of its own.
constexpr double kNeedle = 1e-12;

class SmallTriangleSphereAlgorithm : public ManifoldAlgorithm {
 public:
  SmallTriangleSphereAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* body0,
                               const btCollisionObjectWrapper* body1, bool swapped)
      : ManifoldAlgorithm(ci, body0, body1), swapped_(swapped) {}

  void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                        const btDispatcherInfo& info, btManifoldResult* result) override {
    const btCollisionObjectWrapper* sphere_wrap = swapped_ ? body1 : body0;
    const btCollisionObjectWrapper* triangle_wrap = swapped_ ? body0 : body1;
    auto* sphere = static_cast<btSphereShape*>(const_cast<btCollisionShape*>(sphere_wrap->getCollisionShape()));
    auto* triangle = static_cast<btTriangleShape*>(const_cast<btCollisionShape*>(triangle_wrap->getCollisionShape()));
    btPersistentManifold* manifold = manifoldFor(body0->getCollisionObject(), body1->getCollisionObject());
    result->setPersistentManifold(manifold);
    const btScalar threshold = manifold->getContactBreakingThreshold() + result->m_closestPointDistanceThreshold;
    const btVector3* v = triangle->m_vertices1;
    if (bulletSeesTriangle(v[0], v[1], v[2])) {
      // Bullet's own test, called as btSphereTriangleCollisionAlgorithm calls it.
      SphereTriangleDetector detector(sphere, triangle, threshold);
      btDiscreteCollisionDetectorInterface::ClosestPointInput input;
      input.m_maximumDistanceSquared = btScalar(BT_LARGE_FLOAT);
      input.m_transformA = sphere_wrap->getWorldTransform();
      input.m_transformB = triangle_wrap->getWorldTransform();
      detector.getClosestPoints(input, *result, info.m_debugDraw, swapped_);
    } else {
      smallTriangleContact(*sphere, v, sphere_wrap->getWorldTransform(), triangle_wrap->getWorldTransform(), double(threshold),
                           *result);
    }
    if (ownsManifold()) result->refreshContactPoints();
  }

 private:
  // The contact with a triangle Bullet's test skips: at its nearest point to the centre.
  void smallTriangleContact(const btSphereShape& sphere, const btVector3* v, const btTransform& world_from_sphere,
                            const btTransform& world_from_triangle, double threshold, btManifoldResult& result) const {
    const Eigen::Vector3d a = toEigen(v[0]), b = toEigen(v[1]), c = toEigen(v[2]);
    const Eigen::Vector3d face = (b - a).cross(c - a);
    const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    if (!(face.norm() > kNeedle * longest)) return;
    const Eigen::Vector3d centre = toEigen(world_from_triangle.inverseTimes(world_from_sphere).getOrigin());
    const Eigen::Vector3d w = mesh::closestBarycentric(a, b, c, centre);
    const Eigen::Vector3d nearest = w[0] * a + w[1] * b + w[2] * c;
    const double radius = double(sphere.getRadius());
    const double distance = (centre - nearest).norm();
    if (distance >= radius + threshold) return;
    // From the triangle towards the centre; the face's own normal, turned to the centre's side,
    // where the centre lies on the triangle.
    Eigen::Vector3d normal = face.normalized();
    if (distance > 1e-12 * std::sqrt(longest)) normal = (centre - nearest) / distance;
    else if (normal.dot(centre - a) < 0.0) normal = -normal;
    const double depth = distance - radius;
    const btVector3 normal_on_triangle = world_from_triangle.getBasis() * toBt(normal);
    const btVector3 point_on_triangle = world_from_triangle * toBt(nearest);
    if (swapped_) {
      // As Bullet reports a swapped pair: the normal on the sphere, the point on its surface.
      result.addContactPoint(-normal_on_triangle, point_on_triangle + normal_on_triangle * btScalar(depth), btScalar(depth));
    } else {
      result.addContactPoint(normal_on_triangle, point_on_triangle, btScalar(depth));
    }
  }

  bool swapped_;
};

struct SmallTriangleSphereCreateFunc : btCollisionAlgorithmCreateFunc {
  explicit SmallTriangleSphereCreateFunc(bool swapped) { m_swapped = swapped; }
  btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                 const btCollisionObjectWrapper* body0,
                                                 const btCollisionObjectWrapper* body1) override {
    return ManifoldAlgorithm::create<SmallTriangleSphereAlgorithm>(ci, body0, body1, m_swapped);
  }
};

}  // namespace

bool bulletSeesTriangle(const btVector3& a, const btVector3& b, const btVector3& c) {
  return (b - a).cross(c - a).length2() >= SIMD_EPSILON * SIMD_EPSILON;
}

void registerSmallTriangleSphere(btCollisionDispatcher& dispatcher) {
  static SmallTriangleSphereCreateFunc direct(false);
  static SmallTriangleSphereCreateFunc swapped(true);
  dispatcher.registerCollisionCreateFunc(SPHERE_SHAPE_PROXYTYPE, TRIANGLE_SHAPE_PROXYTYPE, &direct);
  dispatcher.registerCollisionCreateFunc(TRIANGLE_SHAPE_PROXYTYPE, SPHERE_SHAPE_PROXYTYPE, &swapped);
}

}  // namespace thx::phys
