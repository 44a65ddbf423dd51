#include "clients/physics_client/physics_scene.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "clients/physics/bullet_convert.hpp"
#include "scenes/scene_frames.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_mesh.hpp"
#include "scenes/surface_texture.hpp"
#include "textures/height_from_normals.hpp"
#include "textures/smoothing.hpp"

namespace thx::physclient {

namespace {

scene::SceneSurface buildSurface(const scene::Scene& scene) {
  scene::SurfaceTextureOptions options;
  options.smooth = tex::smoothTexture;
  return scene::buildSceneSurface(scene, options);
}

// A manifold point counts as touching when it is closed (or the solver pushed through it).
constexpr double kTouchDistance_m = 1e-5;

// Ordering of a pair: the surface is always b, then the pen; otherwise the lower index is a.
bool aIsFirst(int id0, int id1) {
  if (id0 == kBodySurface) return false;
  if (id1 == kBodySurface) return true;
  if (id0 == kBodyPen) return false;
  if (id1 == kBodyPen) return true;
  return id0 < id1;
}

}  // namespace

phys::BodyMaterial materialOf(const scene::Material& m) {
  phys::BodyMaterial b;
  b.friction = m.friction;
  b.restitution = m.restitution;
  b.rolling_friction = m.rolling_friction_m;
  b.spinning_friction = m.spinning_friction_m;
  return b;
}

PhysicsScene::PhysicsScene(const scene::Scene& scene, const SimOptions& options)
    : scene_(scene),
      options_(options),
      scene_surface_(buildSurface(scene)) {
  world_ = std::make_unique<phys::PhysicsWorld>(options.world);
  const phys::BodyMaterial plane_material = materialOf(scene.surface.material);
  if (scene.surface.mesh) {
    mesh_ = std::make_unique<MeshGround>(scene, surface());
    // hapticd's hello names a mesh scene by the texture and the mesh together.
    scene_surface_.fingerprint = scene::meshSceneFingerprint(scene_surface_.fingerprint, mesh_->sceneMesh());
    plane_ = &mesh_->addTo(*world_, plane_material);
  } else {
    plane_ = surface().usesRelief() ? &world_->addReliefPlane(surface(), plane_material)
                                    : &world_->addNormalMapPlane(surface(), plane_material);
  }
  plane_->setUserIndex(kBodySurface);
  // Textured objects on a normal-mapped plane meet the relief its normals integrate to, as on a
  // mesh (MeshGround), so both textures shape their contacts; the other bodies meet the plane.
  const bool textured_objects = std::any_of(scene.objects.begin(), scene.objects.end(),
                                            [](const scene::SceneObject& o) { return o.texture.has_value(); });
  if (!mesh_ && !surface().usesRelief() && textured_objects) {
    tex::ReliefOfNormals relief = tex::reliefFromNormals(surface().map(), surface().mapping().size_m,
                                                         surface().sampling().address, "the relief of the plane's normal map");
    plane_relief_map_.emplace(std::move(relief.relief));
    plane_relief_ = tex::TexturedSurface(*plane_relief_map_, surface().mapping(), surface().sampling(), true);
    world_->addTexturedObjectsRelief(*plane_, plane_relief_, relief.mean_slope, plane_material)
        .setUserIndex(kBodySurface);
  }

  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const scene::SceneObject& o = scene.objects[i];
    const Eigen::Isometry3d pose = scene::toIsometry(o.pose);
    const double mass = o.fixed ? 0.0 : o.mass_kg;
    const phys::BodyMaterial material = materialOf(o.material);
    btRigidBody* body = nullptr;
    // A textured box's faces or a ball's bump map (issue 29).
    phys::FaceTexture faces;
    if (o.texture) {
      tex::LoadReport report;
      scene::SurfaceTextureOptions texture_options;
      texture_options.report = &report;
      object_textures_.push_back(std::make_unique<tex::TextureMap>(scene::buildObjectTexture(scene, i, texture_options)));
      for (std::string& w : report.warnings) object_texture_warnings_.push_back(std::move(w));
      faces.map = object_textures_.back().get();
      faces.tile_m = o.texture->tile_m;
    }
    switch (o.shape) {
      case scene::Shape::Sphere:
        body = o.texture ? &world_->addTexturedSphere(o.radius_m, mass, pose, material, faces)
                         : &world_->addSphere(o.radius_m, mass, pose, material);
        break;
      case scene::Shape::Box:
        if (o.texture) {
          body = &world_->addTexturedBox(0.5 * o.size_m, mass, pose, material, faces);
        } else {
          body = &world_->addBox(0.5 * o.size_m, mass, pose, material);
        }
        break;
      case scene::Shape::Capsule:
        body = &world_->addCapsule(o.radius_m, 0.5 * o.length_m, mass, pose, material);
        break;
      case scene::Shape::Cylinder:
        body = &world_->addCylinder(o.radius_m, 0.5 * o.length_m, mass, pose, material);
        break;
    }
    body->setUserIndex(int(i));
    if (!o.fixed) phys::setVelocity(*body, o.velocity_m_per_s, o.angular_velocity_rad_per_s);
    objects_.push_back(body);
  }
  v_before_.resize(objects_.size(), Eigen::Vector3d::Zero());

  if (options.pen_devices.empty())
    addPens(options.pens);
  else
    addPens(options.pen_devices);
}

void PhysicsScene::addPens(int count) {
  std::vector<int> devices;
  for (int i = 0; i < count; ++i) devices.push_back(i < penCount() ? pens_[std::size_t(i)].device : i);
  addPens(devices);
}

PhysicsScene::PenBody PhysicsScene::bodyFor(int device) const {
  const PenOptions& pen = options_.pen;
  if (pen.scene_tool && !pen.coupled() && device >= 0 && std::size_t(device) < scene::deviceCount(scene_)) {
    const scene::Tool& tool = scene::deviceAt(scene_, std::size_t(device)).tool;
    if (tool.shape == scene::ToolShape::Capsule) return PenBody{PenShape::Capsule, tool.radius_m, tool.length_m, true};
  }
  return PenBody{pen.shape, pen.radius_m, pen.length_m, false};
}

void PhysicsScene::addPens(const std::vector<int>& devices) {
  for (std::size_t i = 0; i < devices.size(); ++i) {
    if (i < pens_.size() && pens_[i].device == devices[i]) continue;
    if (i < pens_.size()) {  // follows another device now (before the first step): its body anew
      if (pens_[i].body) world_->world().removeRigidBody(pens_[i].body);
      pens_[i] = Pen{};
    } else {
      pens_.emplace_back();
    }
    makePen(int(i), devices[i]);
  }
}

void PhysicsScene::makePen(int index, int device) {
  const PenOptions& pen = options_.pen;
  Pen& p = pens_[std::size_t(index)];
  p.device = device;
  p.geometry = bodyFor(device);
  const PenBody& g = p.geometry;
  if (g.shape == PenShape::None) return;
  // Parked 10 m above the plane until the first pose arrives.
  Eigen::Isometry3d parked = surface().mapping().plane_to_world;
  parked.translation() += 10.0 * surface().mapping().geometricNormalWorld();
  phys::BodyMaterial pen_material;
  pen_material.friction = pen.material_friction;
  pen_material.restitution = 0.0;
  // Kinematic: added with mass 0 (so Bullet files it with the static bodies: it never collides
  // with the plane, the fixed obstacles or another pen), then made kinematic so its velocity
  // comes from its moves. Coupled: dynamic, filtered to meet the dynamic objects only.
  const double mass = pen.coupled() ? pen.coupling_mass_kg : 0.0;
  p.body = g.shape == PenShape::Sphere ? &world_->addSphere(g.radius_m, mass, parked, pen_material)
                                       : &world_->addCapsule(g.radius_m, 0.5 * g.length_m, mass, parked, pen_material);
  if (pen.coupled()) {
    btDiscreteDynamicsWorld& w = world_->world();
    w.removeRigidBody(p.body);
    p.body->setFlags(p.body->getFlags() | BT_DISABLE_WORLD_GRAVITY);
    p.body->setGravity(btVector3(0, 0, 0));
    p.body->setAngularFactor(0.0);
    p.body->setDamping(0.0, 0.0);
    w.addRigidBody(p.body, btBroadphaseProxy::CharacterFilter, btBroadphaseProxy::DefaultFilter);
  } else {
    p.body->setCollisionFlags(p.body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  }
  p.body->setActivationState(DISABLE_DEACTIVATION);
  p.body->setUserIndex(kBodyPen);
  p.body->setUserIndex2(index);
}

std::string coarseReliefWarning(const std::string& ball, double radius_m, const Eigen::Vector2d& texel_m,
                                const Eigen::Vector2d& surface_m) {
  const double texel = texel_m.maxCoeff(), enough = kCoarseTexelPerRadius * radius_m;
  if (!(texel > enough)) return {};
  char text[640];
  std::snprintf(text, sizeof text,
                "ball '%s' (radius %.2f mm) on relief texels of %.2f mm: where the relief has features at its texels, "
                "a ball's contacts stand at texel centres, and it can jitter there where a texel is over %.2f of its "
                "radius; texels of %.2f mm or less would do (%d x %d over the %.3f x %.3f m surface)",
                ball.c_str(), 1e3 * radius_m, 1e3 * texel, kCoarseTexelPerRadius, 1e3 * enough,
                int(std::ceil(surface_m.x() / enough)), int(std::ceil(surface_m.y() / enough)), surface_m.x(), surface_m.y());
  return text;
}

std::vector<std::string> PhysicsScene::warnings() const {
  const auto& objects = scene_.objects;
  std::vector<std::string> out = object_texture_warnings_;
  if (mesh_) return out;
  const tex::TexturedSurface& plane = surface();
  // A normal map's plain balls meet the flat plane; its balls with bump maps, its relief.
  const bool relief = plane.usesRelief();
  const Eigen::Vector2d texel = plane.mapping().texelSize(plane.map());
  for (const scene::SceneObject& o : objects) {
    if (o.shape != scene::Shape::Sphere || o.fixed || (!relief && !o.texture)) continue;
    std::string w = coarseReliefWarning(o.name, o.radius_m, texel, plane.mapping().size_m);
    if (!w.empty()) out.push_back(std::move(w));
  }
  return out;
}

PhysicsScene::~PhysicsScene() = default;

int PhysicsScene::idOf(const btCollisionObject* o) const { return o->getUserIndex(); }

int PhysicsScene::penOf(const btCollisionObject* o) { return o->getUserIndex() == kBodyPen ? o->getUserIndex2() : -1; }

Eigen::Isometry3d PhysicsScene::penPoseFor(const Pen& p) const {
  Eigen::Isometry3d pose = surface().mapping().plane_to_world;  // capsule axis = the plane's normal
  if (p.geometry.along_device) {
    pose.linear() = p.q.toRotationMatrix();
    pose.translation() = p.tip + p.q * Eigen::Vector3d(0, 0, 0.5 * p.geometry.length_m);
    return pose;
  }
  const Eigen::Vector3d n = surface().mapping().geometricNormalWorld();
  const PenBody& g = p.geometry;
  const double up = g.shape == PenShape::Capsule ? g.radius_m + 0.5 * g.length_m : g.radius_m;
  pose.translation() = p.tip + up * n;
  return pose;
}

void PhysicsScene::setPenOrientation(int pen, const Eigen::Quaterniond& q_world) {
  Pen& p = pens_.at(std::size_t(pen));
  const double norm = q_world.norm();
  if (!std::isfinite(norm) || norm < 1e-6) return;  // keep the last good orientation
  p.q = q_world.normalized();
}

void PhysicsScene::setPenTip(int pen, const Eigen::Vector3d& tip_world) {
  Pen& p = pens_.at(std::size_t(pen));
  if (!tip_world.allFinite()) return;  // keep the last good pose
  p.tip = tip_world;
  p.set = true;
}

Eigen::Vector3d PhysicsScene::couplingForce(const Pen& p) const {
  const double k = options_.pen.coupling_n_per_m;
  const double b = 2.0 * std::sqrt(k * options_.pen.coupling_mass_kg);  // critical
  return k * (p.target - phys::positionOf(*p.body)) + b * (p.v_target - phys::velocityOf(*p.body));
}

void PhysicsScene::placePens(double dt_s) {
  for (Pen& p : pens_) {
    if (p.body == nullptr || !p.set) continue;
    const Eigen::Isometry3d pose = penPoseFor(p);
    const btTransform t = phys::toBt(pose);
    if (options_.pen.coupled()) {
      // A teleport puts the body at its target at rest; otherwise the spring pulls it there.
      const bool teleport = !p.placed || (p.target - pose.translation()).norm() > options_.pen.teleport_m;
      p.v_target = teleport ? Eigen::Vector3d::Zero() : Eigen::Vector3d((pose.translation() - p.target) / dt_s);
      p.target = pose.translation();
      if (teleport) {
        p.body->setWorldTransform(t);
        p.body->setInterpolationWorldTransform(t);
        p.body->setLinearVelocity(btVector3(0, 0, 0));
      }
      p.body->setAngularVelocity(btVector3(0, 0, 0));
      p.body->applyCentralForce(phys::toBt(couplingForce(p)));
      p.placed = true;
      continue;
    }
    const Eigen::Vector3d old = phys::toEigen(p.body->getWorldTransform().getOrigin());
    p.body->setWorldTransform(t);
    // A teleport gets no velocity (Bullet derives a kinematic body's velocity from the move since
    // the previous step: interpolation transform -> world transform).
    if (!p.placed || (old - pose.translation()).norm() > options_.pen.teleport_m) p.body->setInterpolationWorldTransform(t);
    p.placed = true;
  }
}

void PhysicsScene::step(double dt_s) {
  placePens(dt_s);
  for (std::size_t i = 0; i < objects_.size(); ++i) v_before_[i] = phys::velocityOf(*objects_[i]);
  world_->step(dt_s);
  ++steps_;
  sim_time_ = double(steps_) * dt_s;
  collectContacts(dt_s);
}

void PhysicsScene::collectContacts(double dt_s) {
  impacts_.clear();
  for (Pen& pen : pens_) pen.force = PenForce{};
  std::set<PairKey> touching_now;
  btDispatcher* dispatcher = world_->world().getDispatcher();

  const int manifolds = dispatcher->getNumManifolds();
  for (int m = 0; m < manifolds; ++m) {
    const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
    const btCollisionObject* o0 = manifold->getBody0();
    const btCollisionObject* o1 = manifold->getBody1();
    const int id0 = idOf(o0), id1 = idOf(o1);
    const bool a_first = aIsFirst(id0, id1);
    const btCollisionObject* oa = a_first ? o0 : o1;
    const btCollisionObject* ob = a_first ? o1 : o0;
    const int ida = a_first ? id0 : id1, idb = a_first ? id1 : id0;
    // The pen in this pair (a pen is b unless the other is the surface, which pens never touch).
    const int pen_index = std::max(penOf(o0), penOf(o1));
    Pen* pen = pen_index >= 0 ? &pens_[std::size_t(pen_index)] : nullptr;
    const Eigen::Vector3d v_pen = pen ? phys::velocityOf(*pen->body) : Eigen::Vector3d::Zero();
    // Bullet's normal points from body1 towards body0; ours from b towards a.
    const double sign = a_first ? 1.0 : -1.0;

    int points = 0;
    double impulse = 0.0;
    Eigen::Vector3d p = Eigen::Vector3d::Zero(), n = Eigen::Vector3d::Zero();
    int mesh_triangle = -1;  // on a mesh surface: the triangle of the first touching point
    for (int k = 0; k < manifold->getNumContacts(); ++k) {
      const btManifoldPoint& pt = manifold->getContactPoint(k);
      if (double(pt.getDistance()) > kTouchDistance_m && pt.getAppliedImpulse() <= 0) continue;
      ++points;
      if (mesh_ && mesh_triangle < 0 && (id0 == kBodySurface || id1 == kBodySurface))
        mesh_triangle = id0 == kBodySurface ? pt.m_index0 : pt.m_index1;
      const Eigen::Vector3d n_bt = phys::toEigen(pt.m_normalWorldOnB);
      impulse += double(pt.getAppliedImpulse());
      n += sign * n_bt;
      p += 0.5 * (phys::toEigen(pt.getPositionWorldOnA()) + phys::toEigen(pt.getPositionWorldOnB()));
      if (pen && !options_.pen.coupled()) {
        // Impulse on body0 = +n_bt j + d1 j1 + d2 j2 (Bullet's solver convention); body1 gets the opposite.
        Eigen::Vector3d j_on_0 = n_bt * double(pt.getAppliedImpulse());
        if (options_.pen.friction)
          j_on_0 += phys::toEigen(pt.m_lateralFrictionDir1) * double(pt.m_appliedImpulseLateral1) +
                    phys::toEigen(pt.m_lateralFrictionDir2) * double(pt.m_appliedImpulseLateral2);
        const bool pen_is_0 = id0 == kBodyPen;
        pen->force.raw_world += (pen_is_0 ? j_on_0 : Eigen::Vector3d(-j_on_0)) / dt_s;
      }
    }
    if (points == 0) continue;
    p /= double(points);
    if (n.norm() > 0) n.normalize();
    if (pen) pen->force.in_contact = true;

    const PairKey key{oa, ob};
    touching_now.insert(key);

    // Velocities at the contact point.
    const auto* ra = btRigidBody::upcast(oa);
    const auto* rb = btRigidBody::upcast(ob);
    auto pointVelocity = [&](const btRigidBody* r, int id) -> Eigen::Vector3d {
      if (r == nullptr || id == kBodySurface) return Eigen::Vector3d::Zero();
      if (id == kBodyPen) return v_pen;
      const Eigen::Vector3d c = phys::positionOf(*r);
      return phys::velocityOf(*r) + phys::angularVelocityOf(*r).cross(p - c);
    };
    const Eigen::Vector3d rel = pointVelocity(ra, ida) - pointVelocity(rb, idb);
    const Eigen::Vector3d slip = rel - rel.dot(n) * n;

    // A mesh contact whose triangle Bullet did not name (it always does for a triangle mesh)
    // counts as an object-object contact rather than a texel of nowhere.
    const std::size_t triangles = mesh_ ? mesh_->sceneMesh().mesh.triangles.size() : 0;
    const bool on_surface = idb == kBodySurface && (!mesh_ || (mesh_triangle >= 0 && std::size_t(mesh_triangle) < triangles));
    Texel texel;
    if (on_surface && mesh_) {
      mesh_->texelOf(mesh_->on(std::uint32_t(mesh_triangle), p).uv, texel.i, texel.j);
    } else if (on_surface) {
      const Eigen::Vector3d local = surface().toLocal(p);
      surface().texelContaining(local.x(), local.y(), texel.i, texel.j);
    }

    const bool new_touch = touching_since_.find(key) == touching_since_.end();
    if (new_touch) {
      auto before = [&](int id) -> Eigen::Vector3d {
        if (id >= 0 && std::size_t(id) < v_before_.size()) return v_before_[std::size_t(id)];
        if (id == kBodyPen) return v_pen;
        return Eigen::Vector3d::Zero();
      };
      const double v_approach = -(before(ida) - before(idb)).dot(n);
      if (v_approach >= options_.impact_min_speed_m_per_s) {
        Impact im;
        im.step = steps_;
        im.sim_time_s = sim_time_;
        im.body_a = ida;
        im.body_b = idb;
        im.impulse_ns = impulse;
        im.v_approach_m_per_s = v_approach;
        im.p_world = p;
        im.n_world = n;
        im.on_surface = on_surface;
        im.texel_i = texel.i;
        im.texel_j = texel.j;
        im.pen = pen_index;
        impacts_.push_back(im);
      }
    }

    LastingContact& c = contacts_[key];
    c.body_a = ida;
    c.mass_a_kg = ida >= 0 && !scene_.objects[std::size_t(ida)].fixed ? scene_.objects[std::size_t(ida)].mass_kg : 0.0;
    c.body_b = idb;
    c.p_world = p;
    c.n_world = n;
    c.v_slip_world = slip;
    c.v_world = (ra && ida >= 0) ? phys::velocityOf(*ra) : (ida == kBodyPen ? v_pen : Eigen::Vector3d::Zero());
    c.impulse_sum_ns += impulse;
    c.window_s += dt_s;
    if (on_surface) extendPath(key, oa, dt_s, std::uint32_t(std::max(mesh_triangle, 0)), c);
  }

  // Pairs that stopped touching forget their path, so a new touch starts a new one.
  for (auto it = last_path_point_.begin(); it != last_path_point_.end();)
    it = touching_now.count(it->first) ? std::next(it) : last_path_point_.erase(it);
  touching_since_.clear();
  for (const PairKey& k : touching_now) touching_since_[k] = steps_;

  for (Pen& pen : pens_) {  // each pen's device gets its own force, clamped on its own
    PenForce& f = pen.force;
    // A coupled pen's device feels the coupling pulling it towards the pen (after this step).
    if (options_.pen.coupled() && pen.body != nullptr && pen.placed) f.raw_world = -couplingForce(pen);
    Eigen::Vector3d sent = options_.pen.force_scale * f.raw_world;
    const double norm = sent.norm();
    if (!std::isfinite(norm)) {
      sent.setZero();
      f.clamped = true;
    } else if (norm > options_.pen.max_force_n) {
      sent *= options_.pen.max_force_n / norm;
      f.clamped = true;
    }
    f.sent_world = sent;
  }
}

void PhysicsScene::extendPath(const PairKey& key, const btCollisionObject* a, double dt_s, std::uint32_t triangle,
                              LastingContact& c) {
  if (mesh_) {
    const MeshGround::Place foot = mesh_->footOf(phys::toEigen(a->getWorldTransform().getOrigin()), triangle);
    const auto last = last_path_point_.find(key);
    extendMeshPath(a, last == last_path_point_.end() ? nullptr : &last->second, foot, dt_s, c);
    PathPoint& point = last_path_point_[key];
    point.p_world = foot.p_world;
    point.uv = foot.uv;
    return;
  }
  const tex::TexturedSurface& s = surface();
  // The point under a's centre of mass: it moves with the body, not with the sampled normal
  // (docs/physics.md, "Texel paths").
  const Eigen::Vector3d centre = s.toLocal(phys::toEigen(a->getWorldTransform().getOrigin()));
  const tex::TexCoord uv = s.mapping().uvOfLocal({centre.x(), centre.y()});
  auto add = [&](long long i, long long j, double t_s, const Eigen::Vector3d& v_world) {
    if (c.path.size() >= LastingContact::kMaxPath) return ++c.path_dropped, void();
    const int ri = tex::resolveIndex(i, s.map().width(), s.sampling().address);
    const int rj = tex::resolveIndex(j, s.map().height(), s.sampling().address);
    c.path.push_back({i, j, t_s, s.directionToWorld(s.texelNormal(i, j, ri, rj)), v_world});
  };
  const Eigen::Vector2d xy(centre.x(), centre.y());
  const auto last = last_path_point_.find(key);
  if (last == last_path_point_.end()) {  // a new touch: the texel it starts on
    long long i = 0, j = 0;
    s.texelContaining(xy.x(), xy.y(), i, j);
    const btRigidBody* body = btRigidBody::upcast(a);
    const Eigen::Vector3d v_local = s.directionToLocal(body ? phys::velocityOf(*body) : Eigen::Vector3d::Zero());
    add(i, j, sim_time_, s.directionToWorld({v_local.x(), v_local.y(), 0.0}));
  } else {
    const Eigen::Vector2d v_xy = (xy - last->second.xy_local) / dt_s;
    const Eigen::Vector3d v_world = s.directionToWorld({v_xy.x(), v_xy.y(), 0.0});
    const double t0 = sim_time_ - dt_s;
    bool first = true;  // the walk starts in the texel the path entered at an earlier step
    tex::walkCells(s.map(), last->second.uv, uv, [&](long long i, long long j, double t_enter) {
      if (!first) add(i, j, t0 + t_enter * dt_s, v_world);
      first = false;
      return true;
    });
  }
  last_path_point_[key] = {xy, Eigen::Vector3d::Zero(), uv};
}

void PhysicsScene::extendMeshPath(const btCollisionObject* a, const PathPoint* from, const MeshGround::Place& to,
                                  double dt_s, LastingContact& c) {
  auto add = [&](long long i, long long j, double t_s, const Eigen::Vector3d& v_world) {
    if (c.path.size() >= LastingContact::kMaxPath) return ++c.path_dropped, void();
    c.path.push_back({i, j, t_s, mesh_->texelNormalWorld(i, j, to), v_world});
  };
  const tex::TextureMap& map = surface().map();
  if (from == nullptr) {  // a new touch: the texel it starts on, with the body's velocity
    long long i = 0, j = 0;
    mesh_->texelOf(to.uv, i, j);
    const btRigidBody* body = btRigidBody::upcast(a);
    add(i, j, sim_time_, body ? phys::velocityOf(*body) : Eigen::Vector3d::Zero());
    return;
  }
  const Eigen::Vector3d& from_world = from->p_world;
  const tex::TexCoord& from_uv = from->uv;
  const Eigen::Vector3d v_world = (to.p_world - from_world) / dt_s;
  // Texels the foot can have crossed at the texture's scale here (and two for rounding): a uv step
  // longer than that jumped a seam of the mesh's uv (a lathe's u from 1 back to 0), where the
  // path starts again in the texel it lands in.
  const double moved = (to.p_world - from_world).norm();
  const double du = std::fabs(to.uv.u - from_uv.u) * map.width(), dv = std::fabs(to.uv.v - from_uv.v) * map.height();
  const double can_u = 2.0 * moved / (to.metres_per_uv.x() / map.width()) + 2.0;
  const double can_v = 2.0 * moved / (to.metres_per_uv.y() / map.height()) + 2.0;
  if (!(du <= can_u && dv <= can_v)) {
    long long i = 0, j = 0;
    mesh_->texelOf(to.uv, i, j);
    add(i, j, sim_time_, v_world);
    return;
  }
  const double t0 = sim_time_ - dt_s;
  bool first = true;  // the walk starts in the texel the path entered at an earlier step
  tex::walkCells(map, from_uv, to.uv, [&](long long i, long long j, double t_enter) {
    if (!first) add(i, j, t0 + t_enter * dt_s, v_world);
    first = false;
    return true;
  });
}

std::vector<LastingContact> PhysicsScene::takeContacts() {
  std::vector<LastingContact> out;
  out.reserve(contacts_.size());
  for (auto& [key, c] : contacts_) out.push_back(std::move(c));
  contacts_.clear();
  return out;
}

BodyState PhysicsScene::body(int id) const {
  BodyState s;
  s.id = id;
  const btRigidBody& b = *objects_.at(std::size_t(id));
  const btTransform& t = b.getWorldTransform();
  s.p_world = phys::toEigen(t.getOrigin());
  const btQuaternion q = t.getRotation();
  s.q_world = Eigen::Quaterniond(double(q.w()), double(q.x()), double(q.y()), double(q.z()));
  s.v_world = phys::velocityOf(b);
  s.w_world = phys::angularVelocityOf(b);
  return s;
}

std::vector<BodyState> PhysicsScene::bodies() const {
  std::vector<BodyState> out;
  out.reserve(objects_.size());
  for (std::size_t i = 0; i < objects_.size(); ++i) out.push_back(body(int(i)));
  return out;
}

}  // namespace thx::physclient
