#include "clients/physics/ball_on_object_faces.hpp"

#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>

#include <algorithm>
#include <array>
#include <limits>
#include <utility>

#include "clients/physics/bullet_convert.hpp"
#include "clients/physics/capsule_balls.hpp"
#include "clients/physics/textured_ball.hpp"

namespace thx::phys {

ObjectFaces::ObjectFaces(std::unique_ptr<ObjectGround> surface, const FaceTexture& texture, double sphere_radius_m)
    : ground(std::move(surface)),
      mesh(ground->mesh()),
      contact(ground->relief().mesh),
      ball_relief(*texture.map, texture.sampling.address) {
  options.texture = texture.map;
  options.sampling = texture.sampling;
  // The relief is laid at the scale it was made for: one tile across tile_m.
  options.normals_made_for_m = Eigen::Vector2d::Constant(texture.tile_m);
  options.ball_relief = &ball_relief;
  options.sphere_radius_m = sphere_radius_m;
  texel_m = texture.tile_m / double(std::max(texture.map->width(), texture.map->height()));
}

std::unique_ptr<ObjectFaces> boxFaces(const Eigen::Vector3d& half_extents_m, const FaceTexture& texture) {
  return std::make_unique<ObjectFaces>(boxGround(half_extents_m, &texture), texture, 0.0);
}

std::unique_ptr<ObjectFaces> ballFaces(double radius_m, const FaceTexture& texture, int cells) {
  return std::make_unique<ObjectFaces>(ballGround(radius_m, texture, cells), texture, radius_m);
}

void ObjectFacesCatalog::addBox(const btCollisionShape& box, const Eigen::Vector3d& half_extents_m,
                                const FaceTexture& texture) {
  faces_[&box] = boxFaces(half_extents_m, texture);
}

void ObjectFacesCatalog::addBall(const btCollisionShape& ball, double radius_m, const FaceTexture& texture) {
  faces_[&ball] = ballFaces(radius_m, texture);
}

const ObjectFaces* ObjectFacesCatalog::find(const btCollisionShape& shape) const {
  const auto it = faces_.find(&shape);
  return it == faces_.end() ? nullptr : it->second.get();
}

const ObjectGround* ObjectFacesCatalog::ground(const btCollisionShape& shape) const {
  const ObjectFaces* faces = find(shape);
  return faces ? faces->ground.get() : nullptr;
}

namespace {

using ObjectAxis = BallOnObjectFacesAlgorithm::ObjectAxis;

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

// Which ball of the object made a point: its place along the axis (0 at -half_m, 1 at +half_m),
// kept in the point's index on the object's side (unused for a convex shape). Recovering it from
// the point's place (the axis point nearest it) was exact only where the point's normal is square
// to the axis: over a ball's curve it named a ball up to 0.9 mm along the pen from the one
// searched, and its gap was up to 21 um off the least.
constexpr double kAlongScale = 1e9;
int encodeAlong(double along) { return int(std::lround(std::clamp(along, 0.0, 1.0) * kAlongScale)); }
// The centre (object frame) of the ball at `index` along the axis.
Eigen::Vector3d ballCentreOf(const ObjectAxis& axis, int index) {
  return (2.0 * std::clamp(double(index) / kAlongScale, 0.0, 1.0) - 1.0) * axis.half_m;
}

}  // namespace

Eigen::Vector3d ballCentreOfPoint(const btManifoldPoint& point, const btCollisionShape& object) {
  return ballCentreOf(axisOf(object), point.m_index0);
}

bool meetsFacesAsBalls(const btCollisionShape& shape) {
  const int type = shape.getShapeType();
  return type == CAPSULE_SHAPE_PROXYTYPE || (type == SPHERE_SHAPE_PROXYTYPE && !ballTextureOf(shape));
}

void BallOnObjectFacesAlgorithm::processCollision(const btCollisionObjectWrapper* body0,
                                                  const btCollisionObjectWrapper* body1, const btDispatcherInfo& info,
                                                  btManifoldResult* result) {
  const btCollisionObjectWrapper* textured = faces_first_ ? body0 : body1;
  const btCollisionObjectWrapper* object = faces_first_ ? body1 : body0;
  // (object, textured), whatever order the dispatcher hands the pair in: the textured object is
  // the mesh, body B.
  btPersistentManifold* manifold = manifoldFor(object->getCollisionObject(), textured->getCollisionObject());
  result->setPersistentManifold(manifold);
  const CreaseSides before = creaseSidesOf(*manifold);  // before this step's points are added
  const ObjectAxis axis = axisOf(*object->getCollisionShape());
  const double r = axis.radius_m;
  const Eigen::Isometry3d world_from_mesh = toEigen(textured->getWorldTransform());
  const Eigen::Isometry3d world_from_object = toEigen(object->getWorldTransform());
  const Eigen::Isometry3d mesh_from_world = world_from_mesh.inverse();
  const Eigen::Vector3d a = mesh_from_world * (world_from_object * Eigen::Vector3d(-axis.half_m)),
                        b = mesh_from_world * (world_from_object * axis.half_m);
  const double threshold = double(manifold->getContactBreakingThreshold());

  // The triangles the object's balls can reach, in index order (the BVH's order is its own, and the
  // order points are added in decides which a full manifold keeps).
  near_.clear();
  struct Gather : btTriangleCallback {
    std::vector<int>* out = nullptr;
    void processTriangle(btVector3*, int, int index) override { out->push_back(index); }
  } gather;
  gather.out = &near_;
  const Eigen::Vector3d reach = Eigen::Vector3d::Constant(r + threshold);
  faces_->ground->triangles().processAllTriangles(&gather, toBt(Eigen::Vector3d(a.cwiseMin(b) - reach)),
                                   toBt(Eigen::Vector3d(a.cwiseMax(b) + reach)));
  std::sort(near_.begin(), near_.end());

  // Bullet's sphere-triangle points, for each ball of the object that meets a triangle within
  // reach (capsule_balls.hpp; a sphere's one).
  const mesh::TexturedMesh& mesh = faces_->mesh;
  const double length = (b - a).norm();
  // Each point goes in with its ball's lifted gap, not its distance to the flat triangle: a full
  // manifold keeps its deepest point, and over a relief the flat triangle's deepest is not the
  // relief's (a capsule over the dimpled ball kept points up to 10 um shallower than its least gap).
  const auto liftedGap = [&](std::uint32_t t, double along) {
    return ballLiftedGap(faces_->contact, Eigen::Vector3d(a + along * (b - a)), t, r, faces_->options);
  };
  // `lifted_gap`: nullptr, read here.
  const auto addBall = [&](std::uint32_t t, double along, const double* lifted_gap) {
    const Eigen::Vector3d c = a + along * (b - a);
    const Eigen::Vector3d q = mesh::pointAt(mesh, t, mesh::closestBarycentric(mesh, t, c));
    const Eigen::Vector3d d = c - q;
    const double distance = d.norm();
    if (distance - r > threshold) return;
    const double gap = lifted_gap ? *lifted_gap : liftedGap(t, along);
    // The centre on the face: its outward normal.
    const Eigen::Vector3d n = distance > 1e-12 ? Eigen::Vector3d(d / distance) : mesh::faceNormal(mesh, t);
    if (faces_first_) {
      result->setShapeIdentifiersA(0, int(t));
      result->setShapeIdentifiersB(0, encodeAlong(along));
    } else {
      result->setShapeIdentifiersA(0, encodeAlong(along));
      result->setShapeIdentifiersB(0, int(t));
    }
    result->addContactPoint(toBt(Eigen::Vector3d(world_from_mesh.linear() * n)),
                            toBt(Eigen::Vector3d(world_from_mesh * q)), static_cast<btScalar>(gap));
  };
  // A capsule: the balls on its segment that meet triangle t (capsule_balls.hpp).
  const auto addCapsuleBalls = [&](std::uint32_t t) {
    const mesh::Triangle& corners = mesh.triangles[t];
    const Eigen::Vector3d &p0 = mesh.positions[corners[0]], &p1 = mesh.positions[corners[1]],
                          &p2 = mesh.positions[corners[2]];
    const SegmentOverTriangle over = segmentOverTriangle(p0, p1, p2, a, b);
    // Beside the triangle (its edge nearest): that ball, as Bullet meets it.
    if (!over.runs_over || over.nearest_t < over.lo || over.nearest_t > over.hi)
      addBall(t, over.nearest_t, nullptr);
    if (!over.runs_over) return;
    // Over it, the least lifted gap on each half of the run, searched a texel apart; the run's
    // distance to the plane is least at an end, so none of it is within reach if neither end is.
    const auto distance = [&](double along) { return distanceToTriangle(p0, p1, p2, Eigen::Vector3d(a + along * (b - a))); };
    if (std::min(distance(over.lo), distance(over.hi)) - r > threshold) return;
    const auto gap = [&](double along) { return liftedGap(t, along); };
    const RunBalls balls = leastOnHalves(over.lo, over.hi, faces_->texel_m / length, 1e-9, gap);
    for (int k = 0; k < balls.count; ++k) addBall(t, balls.t[std::size_t(k)], nullptr);
  };
  if (!(length > 0.0)) {
    // A sphere: its centre's ball, one contact with the smooth surface whichever triangles it is
    // found on (applyBallMeshContact moves every point to its centre's foot), its lifted gap read
    // once from the nearest triangle.
    double nearest = std::numeric_limits<double>::infinity();
    std::uint32_t from = 0;
    for (const int index : near_) {
      const auto t = std::uint32_t(index);
      const double distance = (a - mesh::pointAt(mesh, t, mesh::closestBarycentric(mesh, t, a))).norm();
      if (distance < nearest) nearest = distance, from = t;
    }
    if (nearest - r <= threshold) {
      const double gap = liftedGap(from, 0.0);
      if (faces_->options.sphere_radius_m > 0.0) {
        // On a ball, which has no crease, that one point: every other would be rewritten to the
        // same foot, its lift and gradient read again (a marble in a dimple: 120 us a step).
        addBall(from, 0.0, &gap);
      } else {
        // On a box each face within reach keeps its point: past an edge the rewrite reads the
        // faces either side of the reporting triangle's (ballPastCrease).
        for (const int index : near_) addBall(std::uint32_t(index), 0.0, &gap);
      }
    }
  } else if (faces_->options.sphere_radius_m > 0.0) {
    // On a ball the segment's run within reach of its surface is searched once, not triangle by
    // triangle: the least lifted gap on each half of it, sampled a texel apart, each sample's
    // foot walked to from the nearest sample's (the ball's triangles are far smaller than the
    // run: the pen pressing the dimpled ball searched some thirty runs, 250 us a step).
    const double ball_reach = faces_->options.sphere_radius_m + r + threshold;
    // |a + t (b - a)| <= ball_reach, the mesh centred on the ball's centre.
    const Eigen::Vector3d d = b - a;
    const double qa = d.squaredNorm(), qb = 2.0 * a.dot(d), qc = a.squaredNorm() - ball_reach * ball_reach;
    const double discriminant = qb * qb - 4.0 * qa * qc;
    if (discriminant > 0.0 && !near_.empty()) {
      const double root = std::sqrt(discriminant);
      const double lo = std::max(0.0, (-qb - root) / (2.0 * qa)), hi = std::min(1.0, (-qb + root) / (2.0 * qa));
      if (lo <= hi) {
        // Each walk starts from the foot of the sample nearest it, the run's ends from the
        // triangles nearest them (a walk is bounded: from one end to the other of a capsule
        // lying across the ball it stopped short, and the search took up to 21 um more gap).
        const auto triangleNearest = [&](const Eigen::Vector3d& p) {
          std::uint32_t best = std::uint32_t(near_.front());
          double nearest = std::numeric_limits<double>::infinity();
          for (const int index : near_) {
            const mesh::Triangle& c = mesh.triangles[std::size_t(index)];
            const double distance = ((mesh.positions[c[0]] + mesh.positions[c[1]] + mesh.positions[c[2]]) / 3.0 - p).squaredNorm();
            if (distance < nearest) nearest = distance, best = std::uint32_t(index);
          }
          return best;
        };
        trail_.clear();
        trail_.emplace_back(lo, triangleNearest(a + lo * d));
        trail_.emplace_back(hi, triangleNearest(a + hi * d));
        const auto footNear = [&](double along) {
          std::uint32_t from = trail_.front().second;
          double closest = std::numeric_limits<double>::infinity();
          for (const auto& [t, triangle] : trail_)
            if (std::fabs(t - along) < closest) closest = std::fabs(t - along), from = triangle;
          return from;
        };
        const auto gap = [&](double along) {
          std::uint32_t triangle = footNear(along);
          const double g = ballLiftedGapFrom(faces_->contact, Eigen::Vector3d(a + along * d), triangle, r, faces_->options);
          trail_.emplace_back(along, triangle);
          return g;
        };
        const RunBalls balls = leastOnHalves(lo, hi, faces_->texel_m / length, 1e-9, gap);
        for (int k = 0; k < balls.count; ++k) {
          const double along = balls.t[std::size_t(k)];
          std::uint32_t triangle = footNear(along);
          const double g = ballLiftedGapFrom(faces_->contact, Eigen::Vector3d(a + along * d), triangle, r, faces_->options);
          addBall(triangle, along, &g);
        }
      }
    }
  } else {
    // Last step's crease points go: their impulses are in `before`, and this step's balls are
    // found afresh (splitCapsuleAtCreases).
    for (int k = manifold->getNumContacts() - 1; k >= 0; --k)
      if (creaseTagOf(manifold->getContactPoint(k)) != 0) manifold->removeContactPoint(k);
    for (const int index : near_) addCapsuleBalls(std::uint32_t(index));
  }
  result->refreshContactPoints();

  // Every point, kept or new, rewritten as a relief mesh's are (textured_world.cpp does it there
  // after Bullet's detection; here the textured object moves, so relative to it), each by the ball
  // that made it (its index on the object's side: encodeAlong).
  StepContext step = catalog_->solver ? stepContextOf(*catalog_->solver, double(info.m_timeStep)) : StepContext{};
  step.dt_s = double(info.m_timeStep);
  step.surface_body = textured->getCollisionObject();
  if (!(length > 0.0)) {
    // A sphere: its manifold as a whole (one point per side where its lift has a crease).
    const ObjectBall ball{world_from_object.translation(), r};
    applyBallMeshManifold(*manifold, true, world_from_mesh, faces_->contact, ball, *object->getCollisionObject(),
                          faces_->options, step, &before);
    return;
  }
  if (!(faces_->options.sphere_radius_m > 0.0) &&
      splitCapsuleAtCreases(*manifold, axis, world_from_object, world_from_mesh, *object->getCollisionObject(), step, before))
    return;
  for (int k = 0; k < manifold->getNumContacts(); ++k) {
    btManifoldPoint& point = manifold->getContactPoint(k);
    const ObjectBall ball{world_from_object * ballCentreOf(axis, point.m_index0), r};
    applyBallMeshContact(point, true, world_from_mesh, faces_->contact, ball, *object->getCollisionObject(),
                         faces_->options, step);
  }
}

bool BallOnObjectFacesAlgorithm::splitCapsuleAtCreases(btPersistentManifold& manifold, const ObjectAxis& axis,
                                                       const Eigen::Isometry3d& world_from_object,
                                                       const Eigen::Isometry3d& world_from_mesh,
                                                       const btCollisionObject& object, const StepContext& step,
                                                       const CreaseSides& before) {
  const MeshContactOptions& options = faces_->options;
  if (!options.smooth || !options.texture || !options.ball_relief || !options.lift_ball) return false;
  // The balls that made the points (their places along the axis), each read at its first point's
  // foot where all its points' feet are over the surface.
  groups_.clear();
  const int count = manifold.getNumContacts();
  std::array<int, 4> group_of{};
  for (int k = 0; k < count; ++k) {
    const int code = manifold.getContactPoint(k).m_index0;
    std::size_t g = 0;
    while (g < groups_.size() && groups_[g].code != code) ++g;
    if (g == groups_.size()) groups_.push_back({code, k, ObjectBall{world_from_object * ballCentreOf(axis, code), axis.radius_m}, {}});
    group_of[std::size_t(k)] = int(g);
  }
  for (BallGroup& group : groups_) {
    bool over = true;
    for (int k = 0; k < count && over; ++k)
      if (groups_[std::size_t(group_of[std::size_t(k)])].code == group.code)
        over = ballFootIsOverSurface(manifold.getContactPoint(k), true, world_from_mesh, faces_->contact, group.ball);
    // Whether it has a crease under it, not yet split (the same reads as the point's rewrite).
    if (over)
      group.at = ballContactsAtFoot(manifold.getContactPoint(group.first), true, world_from_mesh, faces_->contact, group.ball,
                                    options, false);
  }
  // The balls with a crease under them at the two ends of their run, each as a point on each
  // side of it (slot 0 the nearer the axis's start); the rest of them go (the crease runs under
  // them too, between the two), and the other balls' points stay while there is room.
  const auto creased = [](const BallGroup& group) { return group.at && group.at->contacts.crease; };
  int lowest = -1, highest = -1;
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    if (!creased(groups_[g])) continue;
    if (lowest < 0 || groups_[g].code < groups_[std::size_t(lowest)].code) lowest = int(g);
    if (highest < 0 || groups_[g].code > groups_[std::size_t(highest)].code) highest = int(g);
  }
  if (lowest < 0) {
    // No crease: as applyBallMeshContact rewrites each point (each ball's first point from the
    // contact just read).
    for (int k = 0; k < count; ++k) {
      btManifoldPoint& point = manifold.getContactPoint(k);
      const BallGroup& group = groups_[std::size_t(group_of[std::size_t(k)])];
      if (k == group.first && group.at)
        writeBallContactAtFoot(point, true, world_from_mesh, *group.at, 0, group.ball, object, options, step, manifold);
      else
        applyBallMeshContact(point, true, world_from_mesh, faces_->contact, group.ball, object, options, step);
    }
    return true;
  }
  struct Wanted {
    btManifoldPoint point;
    int group = 0, side = -1;  // side -1: the ball's one contact
  };
  std::array<Wanted, 4> wanted;
  int n = 0;
  // The crease met at the two ends of the capsule's segment where it runs under them (a capsule
  // lying along a groove): the balls the search finds along a level groove are any of the run's,
  // and a slot that moved from an end ball to a middle one for a step kicked the capsule at
  // 0.15 mm/s. Each end's foot walked to from the point whose ball is nearest it.
  ends_.clear();
  for (const int end : {0, 1}) {
    const int code = encodeAlong(double(end));
    int nearest = 0;
    for (int k = 1; k < count; ++k)
      if (std::abs(manifold.getContactPoint(k).m_index0 - code) < std::abs(manifold.getContactPoint(nearest).m_index0 - code))
        nearest = k;
    const ObjectBall ball{world_from_object * ballCentreOf(axis, code), axis.radius_m};
    const std::uint32_t from = std::uint32_t(manifold.getContactPoint(nearest).m_index1);
    std::optional<BallContactsAtFoot> at = ballContactsNear(from, world_from_mesh, faces_->contact, ball, options, true);
    if (at && at->contacts.count == 2) ends_.push_back({code, nearest, ball, at});
  }
  if (ends_.empty()) {
    // Only between the ends (a capsule across a groove): the run's creased balls at its two ends.
    for (const int g : {lowest, highest}) {
      if (g == highest && highest == lowest) break;
      BallGroup group = groups_[std::size_t(g)];
      group.at = ballContactsAtFoot(manifold.getContactPoint(group.first), true, world_from_mesh, faces_->contact,
                                    group.ball, options, true);
      if (group.at && group.at->contacts.count == 2) ends_.push_back(group);
    }
  }
  if (ends_.empty()) {  // a half held no texel: each point as applyBallMeshContact rewrites it
    for (int k = 0; k < count; ++k) {
      const BallGroup& group = groups_[std::size_t(group_of[std::size_t(k)])];
      applyBallMeshContact(manifold.getContactPoint(k), true, world_from_mesh, faces_->contact, group.ball, object, options,
                           step);
    }
    return true;
  }
  for (std::size_t e = 0; e < ends_.size(); ++e) {
    const int slot = ends_.size() == 2 ? int(e) : (ends_[e].code > encodeAlong(0.5) ? 1 : 0);
    for (int side = 0; side < 2; ++side) {
      wanted[std::size_t(n)] = {manifold.getContactPoint(ends_[e].first), -1 - int(e), side};
      btManifoldPoint& point = wanted[std::size_t(n)].point;
      startCreasePoint(point, 1 + side + 2 * slot, &before);
      point.m_index0 = ends_[e].code;  // the ball that made it
      point.m_index1 = int(ends_[e].at->foot_triangle);
      ++n;
    }
  }
  for (int k = 0; k < count && n < 4; ++k) {
    if (creased(groups_[std::size_t(group_of[std::size_t(k)])])) continue;
    wanted[std::size_t(n)] = {manifold.getContactPoint(k), group_of[std::size_t(k)], -1};
    setCreaseTag(wanted[std::size_t(n)].point, 0);
    ++n;
  }
  manifold.clearManifold();
  for (int k = 0; k < n; ++k) {
    btManifoldPoint& point = manifold.getContactPoint(manifold.addManifoldPoint(wanted[std::size_t(k)].point));
    const int g = wanted[std::size_t(k)].group;
    const BallGroup& group = g < 0 ? ends_[std::size_t(-1 - g)] : groups_[std::size_t(g)];
    if (wanted[std::size_t(k)].side >= 0)
      writeBallContactAtFoot(point, true, world_from_mesh, *group.at, wanted[std::size_t(k)].side, group.ball, object,
                             options, step, manifold);
    else
      applyBallMeshContact(point, true, world_from_mesh, faces_->contact, group.ball, object, options, step);
  }
  return true;
}

}  // namespace thx::phys
