#include "clients/physics/ball_on_box_faces.hpp"

#include <BulletCollision/CollisionShapes/btSphereShape.h>

#include "clients/physics/bullet_convert.hpp"
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
}

void BoxFacesCatalog::add(const btCollisionShape& box, const Eigen::Vector3d& half_extents_m,
                          const FaceTexture& texture) {
  faces_[&box] = std::make_unique<BoxFaces>(half_extents_m, texture);
}

const BoxFaces* BoxFacesCatalog::find(const btCollisionShape& box) const {
  const auto it = faces_.find(&box);
  return it == faces_.end() ? nullptr : it->second.get();
}

void BallOnBoxFacesAlgorithm::processCollision(const btCollisionObjectWrapper* body0,
                                               const btCollisionObjectWrapper* body1, const btDispatcherInfo& info,
                                               btManifoldResult* result) {
  const btCollisionObjectWrapper* box = box_first_ ? body0 : body1;
  const btCollisionObjectWrapper* ball = box_first_ ? body1 : body0;
  // (ball, box), whatever order the dispatcher hands the pair in: the box is the mesh, body B.
  btPersistentManifold* manifold = manifoldFor(ball->getCollisionObject(), box->getCollisionObject());
  result->setPersistentManifold(manifold);
  const double r = double(static_cast<const btSphereShape*>(ball->getCollisionShape())->getRadius());
  const Eigen::Isometry3d world_from_box = toEigen(box->getWorldTransform());
  const Eigen::Vector3d c = world_from_box.inverse() * toEigen(ball->getWorldTransform().getOrigin());
  const double threshold = double(manifold->getContactBreakingThreshold());

  // Bullet's sphere-triangle points on each face triangle within reach.
  const mesh::TexturedMesh& mesh = faces_->mesh;
  for (std::uint32_t t = 0; t < std::uint32_t(mesh.triangles.size()); ++t) {
    const Eigen::Vector3d q = mesh::pointAt(mesh, t, mesh::closestBarycentric(mesh, t, c));
    const Eigen::Vector3d d = c - q;
    const double distance = d.norm();
    if (distance - r > threshold) continue;
    Eigen::Vector3d n = d / distance;
    if (!(distance > 1e-12)) {  // the centre on the face: its outward normal
      Eigen::Vector3d tangent;
      double handedness = 1.0;
      mesh::triangleFrame(mesh, t, n, tangent, handedness);
    }
    if (box_first_)
      result->setShapeIdentifiersA(0, int(t));
    else
      result->setShapeIdentifiersB(0, int(t));
    result->addContactPoint(toBt(Eigen::Vector3d(world_from_box.linear() * n)), toBt(Eigen::Vector3d(world_from_box * q)),
                            static_cast<btScalar>(distance - r));
  }
  result->refreshContactPoints();

  // Every point, kept or new, rewritten as a relief mesh's are (textured_world.cpp does it there
  // after Bullet's detection; here the box moves, so relative to it).
  StepContext step = catalog_->solver ? stepContextOf(*catalog_->solver, double(info.m_timeStep)) : StepContext{};
  step.dt_s = double(info.m_timeStep);
  step.surface_body = box->getCollisionObject();
  for (int k = 0; k < manifold->getNumContacts(); ++k)
    applyMeshContact(manifold->getContactPoint(k), true, world_from_box, faces_->contact, *ball->getCollisionObject(),
                     faces_->options, step);
}

}  // namespace thx::phys
