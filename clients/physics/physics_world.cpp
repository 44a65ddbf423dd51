#include "clients/physics/physics_world.hpp"

#include <BulletCollision/BroadphaseCollision/btOverlappingPairCache.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>

#include <algorithm>
#include <limits>

#include "clients/physics/bullet_convert.hpp"
#include "clients/physics/contact_solver.hpp"
#include "clients/physics/relief_collision.hpp"
#include "clients/physics/relief_plane_shape.hpp"
#include "clients/physics/scaled_convex_collision.hpp"
#include "clients/physics/small_triangle_sphere.hpp"
#include "clients/physics/textured_ball.hpp"
#include "textures/height_from_normals.hpp"

#include "base/error.hpp"

namespace thx::phys {

namespace {
btScalar narrow(double v) { return static_cast<btScalar>(v); }
}  // namespace

// A textured object meets the relief standing for a normal-mapped plane, every other body the
// plane itself (addTexturedObjectsRelief); otherwise Bullet's own rule (groups and masks).
struct PhysicsWorld::TexturedObjectsFilter : btOverlapFilterCallback {
  struct StandIn {
    const btCollisionObject* plane;
    const btCollisionObject* relief;
  };
  std::vector<StandIn> stand_ins;

  static bool textured(const btCollisionObject& o) { return hasObjectTexture(*o.getCollisionShape()); }
  bool needBroadphaseCollision(btBroadphaseProxy* p0, btBroadphaseProxy* p1) const override {
    if ((p0->m_collisionFilterGroup & p1->m_collisionFilterMask) == 0 ||
        (p1->m_collisionFilterGroup & p0->m_collisionFilterMask) == 0)
      return false;
    const auto* a = static_cast<const btCollisionObject*>(p0->m_clientObject);
    const auto* b = static_cast<const btCollisionObject*>(p1->m_clientObject);
    for (const StandIn& s : stand_ins) {
      if (a == s.plane || b == s.plane) return !textured(a == s.plane ? *b : *a);
      if (a == s.relief || b == s.relief) return textured(a == s.relief ? *b : *a);
    }
    return true;
  }
};

PhysicsWorld::PhysicsWorld(const WorldOptions& options) : options_(options) {
  configuration_ = std::make_unique<btDefaultCollisionConfiguration>();
  // Several points per step for a box on the plain / normal-mapped plane, so it rests on its
  // face at once instead of collecting one point per step.
  configuration_->setPlaneConvexMultipointIterations(3, 3);
  dispatcher_ = std::make_unique<btCollisionDispatcher>(configuration_.get());
  registerReliefCollision(*dispatcher_);
  // A ball against a mesh's triangles under 0.06 mm^2, which Bullet's own test skips as degenerate
  // (small_triangle_sphere.hpp).
  registerSmallTriangleSphere(*dispatcher_);
  // Convex pairs without an exact Bullet algorithm: GJK/EPA at metre scale (scaled_convex_collision.hpp).
  if (options.scaled_convex_pairs) registerScaledConvexCollision(*dispatcher_);
  // A textured object against a box, or any object against a textured box: the box met as a mesh
  // of its faces by the texture rules (box_ground.hpp); every other pair as registered above.
  box_ground_funcs_ = registerBoxGroundCollision(*dispatcher_, *configuration_, options.scaled_convex_pairs);
  // A textured object on a plain plane: its texture read against the flat plane (plain_plane.hpp).
  plain_plane_funcs_ = registerPlainPlaneCollision(*dispatcher_, *configuration_);
  broadphase_ = std::make_unique<btDbvtBroadphase>();
  // Bullet's solver, except that friction never outlives its contact's normal impulse
  // (contact_solver.hpp: a box on a normal map slid 12 % slow without this).
  auto solver = std::make_unique<ContactSolver>();
  solver->setTexturedBallIterations(options.textured_ball_solver_iterations);
  solver_ = std::move(solver);
  world_ = std::make_unique<TexturedWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(), configuration_.get());
  box_ground_funcs_->faces.solver = &world_->getSolverInfo();
  world_->setGravity(toBt(options.gravity_m_per_s2));
  world_->getSolverInfo().m_numIterations = options.solver_iterations;
  // Each island solved on its own (Bullet batches islands until they hold 128 manifolds and
  // joints into one solve), so that only an island holding a bump-mapped ball's contacts runs its iterations
  // (contact_solver.hpp); the answers of independent islands do not depend on the batching.
  world_->getSolverInfo().m_minimumSolverBatchSize = 1;
  if (options.friction_along_slip) world_->getSolverInfo().m_solverMode |= SOLVER_ENABLE_FRICTION_DIRECTION_CACHING;
  if (options.friction_disc) world_->getSolverInfo().m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;
  world_->setRestOptions(options.rest);
}

PhysicsWorld::~PhysicsWorld() {
  // Bodies leave the world before the world (and its dispatcher) go.
  for (auto& body : bodies_) world_->removeRigidBody(body.get());
}

btRigidBody& PhysicsWorld::addBody(std::unique_ptr<btCollisionShape> shape, double mass_kg,
                                   const Eigen::Isometry3d& pose, const BodyMaterial& material) {
  btVector3 inertia(0, 0, 0);
  if (mass_kg > 0.0) shape->calculateLocalInertia(narrow(mass_kg), inertia);
  btRigidBody::btRigidBodyConstructionInfo info(narrow(mass_kg), nullptr, shape.get(), inertia);
  info.m_startWorldTransform = toBt(pose);
  info.m_friction = narrow(material.friction);
  info.m_restitution = narrow(material.restitution);
  info.m_rollingFriction = narrow(material.rolling_friction);
  info.m_spinningFriction = narrow(material.spinning_friction);
  auto body = std::make_unique<btRigidBody>(info);
  // Haptic scenes: a resting object must still answer a push from the pen at once. It sleeps
  // only by our rest criterion, and a touch wakes it (textured_world.hpp); without that
  // criterion it never sleeps (Bullet's own would put a centimetre ball rolling at 0.5 m/s to
  // sleep after 2 s).
  body->setActivationState(options_.rest.enabled ? ACTIVE_TAG : DISABLE_DEACTIVATION);
  world_->addRigidBody(body.get());
  shapes_.push_back(std::move(shape));
  bodies_.push_back(std::move(body));
  return *bodies_.back();
}

btRigidBody& PhysicsWorld::addTexturedMesh(const mesh::TexturedMesh& mesh, const Eigen::Isometry3d& pose,
                                           const BodyMaterial& material, const MeshContactOptions& options) {
  if (mesh.triangles.empty() || !mesh.hasFrames())
    throw thx::Error(thx::Error::Kind::Config, "mesh " + mesh.source + ": no triangles or no vertex frames; expected a built textured mesh");
  if (mesh.triangles.size() > std::size_t(std::numeric_limits<int>::max() / 3) ||
      mesh.positions.size() > std::size_t(std::numeric_limits<int>::max()))
    throw thx::Error(thx::Error::Kind::Config, "mesh " + mesh.source + ": too many triangles for Bullet's int indices");
  std::unique_ptr<BulletTriangles> arrays = bulletTriangles(mesh);
  auto shape = std::make_unique<btBvhTriangleMeshShape>(arrays->array.get(), true);
  triangle_arrays_.push_back(std::move(arrays));
  const bool relief_map = options.texture && options.texture->isRelief();
  if (options.smooth && (relief_map || options.smooth_chart)) {
    // Boxes, capsules and cylinders meet it on a chart: the relief's, or the smooth surface's alone.
    auto relief = std::make_unique<MeshRelief>(mesh);
    relief->map = relief_map ? options.texture : nullptr;
    if (relief_map) relief->envelopes = buildReliefEnvelopes(*options.texture);
    relief->sampling = options.sampling;
    relief->normals_made_for_m = options.normals_made_for_m;
    relief->grid_intervals = options.chart_grid_intervals;
    attachMeshRelief(*shape, *relief);
    mesh_reliefs_.push_back(std::move(relief));
  }
  btRigidBody& body = addBody(std::move(shape), 0.0, pose, material);
  world_->addTexturedMesh(&body, &mesh, options);
  return body;
}

btRigidBody& PhysicsWorld::addPlainPlane(const Eigen::Isometry3d& plane_to_world, const BodyMaterial& material) {
  auto shape = std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), btScalar(0));
  // Textured objects meet it by their texture (plain_plane.hpp); a normal-mapped plane is not marked.
  markPlainPlane(*shape);
  return addBody(std::move(shape), 0.0, plane_to_world, material);
}

btRigidBody& PhysicsWorld::addNormalMapPlane(const tex::TexturedSurface& surface, const BodyMaterial& material,
                                             const NormalMapOptions& options) {
  btRigidBody& body = addBody(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), btScalar(0)), 0.0,
                              surface.mapping().plane_to_world, material);
  world_->addNormalMapPlane(&body, &surface, options);
  return body;
}

btRigidBody& PhysicsWorld::addReliefPlane(const tex::TexturedSurface& surface, const BodyMaterial& material) {
  return addBody(std::make_unique<ReliefPlaneShape>(surface), 0.0, surface.mapping().plane_to_world, material);
}

btRigidBody& PhysicsWorld::addTexturedObjectsRelief(const btRigidBody& plane, const tex::TexturedSurface& relief,
                                                    const Eigen::Vector2d& mean_slope, const BodyMaterial& material,
                                                    const NormalMapOptions& options) {
  if (!textured_objects_filter_) {
    textured_objects_filter_ = std::make_unique<TexturedObjectsFilter>();
    world_->getPairCache()->setOverlapFilterCallback(textured_objects_filter_.get());
  }
  btRigidBody& body = addReliefPlane(relief, material);
  textured_objects_filter_->stand_ins.push_back({&plane, &body});
  if (mean_slope.norm() > tex::kLevelMeanSlope)
    world_->addLeaningRelief(&body, Eigen::Vector3d(mean_slope.x(), mean_slope.y(), 0.0), options);
  return body;
}

btRigidBody& PhysicsWorld::addStaticShape(std::unique_ptr<btCollisionShape> shape, const Eigen::Isometry3d& pose,
                                          const BodyMaterial& material) {
  return addBody(std::move(shape), 0.0, pose, material);
}

btRigidBody& PhysicsWorld::addSphere(double radius_m, double mass_kg, const Eigen::Isometry3d& pose,
                                     const BodyMaterial& material) {
  return addBody(std::make_unique<btSphereShape>(narrow(radius_m)), mass_kg, pose, material);
}

btRigidBody& PhysicsWorld::addBox(const Eigen::Vector3d& half_extents_m, double mass_kg,
                                  const Eigen::Isometry3d& pose, const BodyMaterial& material) {
  auto shape = std::make_unique<btBoxShape>(toBt(half_extents_m));
  shape->setMargin(narrow(std::min(options_.convex_margin_m, 0.5 * half_extents_m.minCoeff())));
  return addBody(std::move(shape), mass_kg, pose, material);
}

btRigidBody& PhysicsWorld::addTexturedBox(const Eigen::Vector3d& half_extents_m, double mass_kg,
                                          const Eigen::Isometry3d& pose, const BodyMaterial& material,
                                          const FaceTexture& texture) {
  face_textures_.push_back(std::make_unique<FaceTexture>(texture));
  auto shape = std::make_unique<btBoxShape>(toBt(half_extents_m));
  shape->setMargin(narrow(std::min(options_.convex_margin_m, 0.5 * half_extents_m.minCoeff())));
  attachFaceTexture(*shape, *face_textures_.back());
  // A plain ball or a capsule meets its faces as a relief mesh's (ball_on_object_faces.hpp).
  box_ground_funcs_->faces.addBox(*shape, toEigen(shape->getHalfExtentsWithMargin()), *face_textures_.back());
  return addBody(std::move(shape), mass_kg, pose, material);
}

btRigidBody& PhysicsWorld::addTexturedSphere(double radius_m, double mass_kg, const Eigen::Isometry3d& pose,
                                             const BodyMaterial& material, const FaceTexture& texture) {
  ball_textures_.push_back(std::make_unique<GriddedBallTexture>());
  GriddedBallTexture& gridded = *ball_textures_.back();
  static_cast<FaceTexture&>(gridded) = texture;
  ball_grids_.push_back(BallTexelGrid::build(gridded, radius_m));
  gridded.grid = ball_grids_.back().get();
  auto shape = std::make_unique<btSphereShape>(narrow(radius_m));
  attachBallTexture(*shape, gridded);
  // A plain ball or a capsule meets its surface as a relief mesh's (ball_on_object_faces.hpp), and
  // another ball with a bump map or a cylinder on its chart (box_ground.hpp).
  box_ground_funcs_->faces.addBall(*shape, radius_m, gridded);
  return addBody(std::move(shape), mass_kg, pose, material);
}

btRigidBody& PhysicsWorld::addCapsule(double radius_m, double half_length_m, double mass_kg,
                                      const Eigen::Isometry3d& pose, const BodyMaterial& material) {
  return addBody(std::make_unique<btCapsuleShapeZ>(narrow(radius_m), narrow(2.0 * half_length_m)), mass_kg, pose,
                 material);
}

btRigidBody& PhysicsWorld::addCylinder(double radius_m, double half_length_m, double mass_kg,
                                       const Eigen::Isometry3d& pose, const BodyMaterial& material) {
  auto shape = std::make_unique<btCylinderShapeZ>(btVector3(narrow(radius_m), narrow(radius_m), narrow(half_length_m)));
  shape->setMargin(narrow(std::min(options_.convex_margin_m, 0.5 * std::min(radius_m, half_length_m))));
  return addBody(std::move(shape), mass_kg, pose, material);
}

void PhysicsWorld::step(double dt_s) { world_->stepSimulation(narrow(dt_s), 0, narrow(dt_s)); }

Eigen::Vector3d positionOf(const btRigidBody& body) { return toEigen(body.getWorldTransform().getOrigin()); }
Eigen::Vector3d velocityOf(const btRigidBody& body) { return toEigen(body.getLinearVelocity()); }
Eigen::Vector3d angularVelocityOf(const btRigidBody& body) { return toEigen(body.getAngularVelocity()); }
void setVelocity(btRigidBody& body, const Eigen::Vector3d& v, const Eigen::Vector3d& w) {
  body.activate(true);  // a sleeping body would ignore it
  body.setLinearVelocity(toBt(v));
  body.setAngularVelocity(toBt(w));
}

}  // namespace thx::phys
