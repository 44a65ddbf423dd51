#include "clients/physics/ball_on_box_faces.hpp"

#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>

#include <algorithm>

#include "clients/physics/bullet_convert.hpp"
#include "clients/physics/capsule_balls.hpp"
#include "clients/physics/textured_ball.hpp"
#include "meshes/textured_box_mesh.hpp"

namespace thx::phys {

BoxFaces::BoxFaces(const Eigen::Vector3d& half_extents_m, const FaceTexture& texture)
    : mesh(mesh::texturedBoxMesh(2.0 * half_extents_m, texture.tile_m)),
      contact(mesh),
      ball_relief(*texture.map, texture.sampling.address) {
  options.texture = texture.map;
  options.sampling = texture.sampling;
  // The face's relief is laid at the scale it was made for: one tile across tile_m.
  options.normals_made_for_m = Eigen::Vector2d::Constant(texture.tile_m);
  options.ball_relief = &ball_relief;
  texel_m = texture.tile_m / double(std::max(texture.map->width(), texture.map->height()));
}

void BoxFacesCatalog::add(const btCollisionShape& box, const Eigen::Vector3d& half_extents_m,
                          const FaceTexture& texture) {
  faces_[&box] = std::make_unique<BoxFaces>(half_extents_m, texture);
}

const BoxFaces* BoxFacesCatalog::find(const btCollisionShape& box) const {
  const auto it = faces_.find(&box);
  return it == faces_.end() ? nullptr : it->second.get();
}

namespace {

// The object's segment in its own frame (its balls' centres): a capsule's axis, a sphere's centre.
struct ObjectAxis {
  Eigen::Vector3d half_m = Eigen::Vector3d::Zero();  // from the centre to one end
  double radius_m = 0.0;
};

ObjectAxis axisOf(const btCollisionShape& shape) {
  ObjectAxis axis;
  if (shape.getShapeType() == CAPSULE_SHAPE_PROXYTYPE) {
    const auto& capsule = static_cast<const btCapsuleShape&>(shape);
    axis.half_m[capsule.getUpAxis()] = double(capsule.getHalfHeight());
    axis.radius_m = double(capsule.getRadius());
  } else {
    axis.radius_m = double(static_cast<const btSphereShape&>(shape).getRadius());
  }
  return axis;
}

// The centre (object frame) of the ball that made a point whose place on the object is `local`:
// the axis point nearest it.
Eigen::Vector3d ballCentreOf(const ObjectAxis& axis, const Eigen::Vector3d& local) {
  const double length2 = axis.half_m.squaredNorm();
  if (!(length2 > 0.0)) return Eigen::Vector3d::Zero();
  return std::clamp(axis.half_m.dot(local) / length2, -1.0, 1.0) * axis.half_m;
}

}  // namespace

bool meetsBoxFacesAsBalls(const btCollisionShape& shape) {
  const int type = shape.getShapeType();
  return type == CAPSULE_SHAPE_PROXYTYPE || (type == SPHERE_SHAPE_PROXYTYPE && !ballTextureOf(shape));
}

void BallOnBoxFacesAlgorithm::processCollision(const btCollisionObjectWrapper* body0,
                                               const btCollisionObjectWrapper* body1, const btDispatcherInfo& info,
                                               btManifoldResult* result) {
  const btCollisionObjectWrapper* box = box_first_ ? body0 : body1;
  const btCollisionObjectWrapper* object = box_first_ ? body1 : body0;
  // (object, box), whatever order the dispatcher hands the pair in: the box is the mesh, body B.
  btPersistentManifold* manifold = manifoldFor(object->getCollisionObject(), box->getCollisionObject());
  result->setPersistentManifold(manifold);
  const ObjectAxis axis = axisOf(*object->getCollisionShape());
  const double r = axis.radius_m;
  const Eigen::Isometry3d world_from_box = toEigen(box->getWorldTransform());
  const Eigen::Isometry3d world_from_object = toEigen(object->getWorldTransform());
  const Eigen::Isometry3d box_from_world = world_from_box.inverse();
  const Eigen::Vector3d a = box_from_world * (world_from_object * Eigen::Vector3d(-axis.half_m)),
                        b = box_from_world * (world_from_object * axis.half_m);
  const double threshold = double(manifold->getContactBreakingThreshold());

  // Bullet's sphere-triangle points, for each ball of the object that meets a face triangle
  // within reach (capsule_balls.hpp; a sphere's one).
  const mesh::TexturedMesh& mesh = faces_->mesh;
  const double length = (b - a).norm();
  const auto addBall = [&](std::uint32_t t, double along) {
    const Eigen::Vector3d c = a + along * (b - a);
    const Eigen::Vector3d q = mesh::pointAt(mesh, t, mesh::closestBarycentric(mesh, t, c));
    const Eigen::Vector3d d = c - q;
    const double distance = d.norm();
    if (distance - r > threshold) return;
    // The centre on the face: its outward normal.
    const Eigen::Vector3d n = distance > 1e-12 ? Eigen::Vector3d(d / distance) : mesh::faceNormal(mesh, t);
    if (box_first_)
      result->setShapeIdentifiersA(0, int(t));
    else
      result->setShapeIdentifiersB(0, int(t));
    result->addContactPoint(toBt(Eigen::Vector3d(world_from_box.linear() * n)), toBt(Eigen::Vector3d(world_from_box * q)),
                            static_cast<btScalar>(distance - r));
  };
  for (std::uint32_t t = 0; t < std::uint32_t(mesh.triangles.size()); ++t) {
    if (!(length > 0.0)) {  // a sphere: its centre's ball
      addBall(t, 0.0);
      continue;
    }
    const mesh::Triangle& corners = mesh.triangles[t];
    const Eigen::Vector3d &p0 = mesh.positions[corners[0]], &p1 = mesh.positions[corners[1]],
                          &p2 = mesh.positions[corners[2]];
    const SegmentOverTriangle over = segmentOverTriangle(p0, p1, p2, a, b);
    // Beside the triangle (its edge nearest): that ball, as Bullet meets it.
    if (!over.runs_over || over.nearest_t < over.lo || over.nearest_t > over.hi) addBall(t, over.nearest_t);
    if (!over.runs_over) continue;
    // Over it, the least lifted gap on each half of the run, searched a texel apart; the run's
    // distance to the plane is least at an end, so none of it is within reach if neither end is.
    const auto distance = [&](double along) { return distanceToTriangle(p0, p1, p2, Eigen::Vector3d(a + along * (b - a))); };
    if (std::min(distance(over.lo), distance(over.hi)) - r > threshold) continue;
    const auto gap = [&](double along) {
      return ballLiftedGap(faces_->contact, Eigen::Vector3d(a + along * (b - a)), t, r, faces_->options);
    };
    const RunBalls balls = leastOnHalves(over.lo, over.hi, faces_->texel_m / length, 1e-9, gap);
    for (int k = 0; k < balls.count; ++k) addBall(t, balls.t[std::size_t(k)]);
  }
  result->refreshContactPoints();

  // Every point, kept or new, rewritten as a relief mesh's are (textured_world.cpp does it there
  // after Bullet's detection; here the box moves, so relative to it), each by the ball that made
  // it: the axis point nearest its place on the object.
  StepContext step = catalog_->solver ? stepContextOf(*catalog_->solver, double(info.m_timeStep)) : StepContext{};
  step.dt_s = double(info.m_timeStep);
  step.surface_body = box->getCollisionObject();
  for (int k = 0; k < manifold->getNumContacts(); ++k) {
    btManifoldPoint& point = manifold->getContactPoint(k);
    const ObjectBall ball{world_from_object * ballCentreOf(axis, toEigen(point.m_localPointA)), r};
    applyBallMeshContact(point, true, world_from_box, faces_->contact, ball, *object->getCollisionObject(),
                         faces_->options, step);
  }
}

}  // namespace thx::phys
