#include "clients/physics/relief_collision.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btConvexConcaveCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <iterator>
#include <limits>
#include <numbers>
#include <vector>

#include "clients/physics/ball_on_flat_ground.hpp"
#include "clients/physics/box_relief_contacts.hpp"
#include "clients/physics/bullet_convert.hpp"
#include "clients/physics/conforming_contact.hpp"
#include "clients/physics/contact_selection.hpp"
#include "clients/physics/crease_contact.hpp"
#include "clients/physics/edge_contact.hpp"
#include "clients/physics/end_face_contacts.hpp"
#include "clients/physics/manifold_room.hpp"
#include "clients/physics/pair_contact_normal.hpp"
#include "clients/physics/relief_plane_shape.hpp"
#include "clients/physics/relief_raster.hpp"
#include "clients/physics/speculative_contacts.hpp"
#include "clients/physics/textured_ball_basins.hpp"
#include "clients/physics/textured_ball.hpp"
#include "clients/physics/textured_box.hpp"
#include "clients/physics/textured_object_surface.hpp"

namespace thx::phys {

std::optional<Underside> undersideOf(const btCollisionShape& shape, const Eigen::Isometry3d& pose) {
  switch (shape.getShapeType()) {
    case SPHERE_SHAPE_PROXYTYPE:
      return Underside::sphere(pose, double(static_cast<const btSphereShape&>(shape).getRadius()));
    case BOX_SHAPE_PROXYTYPE:
      // With margin: Bullet's box shrinks its core by the margin, the full box is what collides.
      return Underside::box(pose, toEigen(static_cast<const btBoxShape&>(shape).getHalfExtentsWithMargin()));
    case CAPSULE_SHAPE_PROXYTYPE: {
      const auto& c = static_cast<const btCapsuleShape&>(shape);
      return Underside::capsule(pose, double(c.getRadius()), double(c.getHalfHeight()), c.getUpAxis());
    }
    case CYLINDER_SHAPE_PROXYTYPE: {
      const auto& c = static_cast<const btCylinderShape&>(shape);
      const int axis = c.getUpAxis();
      return Underside::cylinder(pose, double(c.getRadius()), double(c.getHalfExtentsWithMargin()[axis]), axis);
    }
    default:
      return std::nullopt;
  }
}

namespace {

// A cylinder's axis's point nearest the origin of the frame `pose` places it in, at least its
// radius in from its end faces (so inside the ball it holds, outside whatever it touches: the
// chart is laid under a point in front of the surface); any other shape's centre.
Eigen::Vector3d rodPointNearestOrigin(const btCollisionShape& shape, const Eigen::Isometry3d& pose) {
  if (shape.getShapeType() != CYLINDER_SHAPE_PROXYTYPE) return pose.translation();
  const auto& c = static_cast<const btCylinderShape&>(shape);
  const int axis = c.getUpAxis();
  const double half = double(c.getHalfExtentsWithMargin()[axis]);
  const double free = half - std::min(half, double(c.getRadius()));
  const Eigen::Vector3d along = pose.linear().col(axis);
  const double t = std::clamp(-along.dot(pose.translation()), -free, free);
  return pose.translation() + t * along;
}

// How far the shape reaches from its centre: the chart under it must cover that far.
double reachOf(const btCollisionShape& shape) {
  switch (shape.getShapeType()) {
    case CAPSULE_SHAPE_PROXYTYPE: {
      const auto& c = static_cast<const btCapsuleShape&>(shape);
      return double(c.getRadius() + c.getHalfHeight());
    }
    case CYLINDER_SHAPE_PROXYTYPE: {
      const auto& c = static_cast<const btCylinderShape&>(shape);
      const btVector3 half = c.getHalfExtentsWithMargin();
      const double radius = double(c.getRadius()), along = double(half[c.getUpAxis()]);
      return std::hypot(radius, along);
    }
    case BOX_SHAPE_PROXYTYPE:
      return toEigen(static_cast<const btBoxShape&>(shape).getHalfExtentsWithMargin()).norm();
    case SPHERE_SHAPE_PROXYTYPE:
      // Its radius: the bound below is its box's corner, sqrt(3) r, and on a ball of its own size
      // the ground's bend was fitted that far out, where the ring's points lie 60 degrees round
      // and were taken for a crease: the bend came out flat (mesh_relief_chart.cpp, fitBend).
      return double(static_cast<const btSphereShape&>(shape).getRadius());
    default: {
      btVector3 centre;
      btScalar radius = 0;
      shape.getBoundingSphere(centre, radius);
      return double(radius + centre.length());
    }
  }
}

// Where a smooth chart's samples go under an object (chart frame): a box's lowest face, so that
// its corners are samples however it is tilted (over its bounds, a tilted box's outer rows fall
// beside its underside's edges, and a block in a bowl sank 0.36 mm onto the samples a row in);
// other shapes' bounds.
Eigen::AlignedBox2d gridFootprint(const Underside& underside) {
  if (underside.kind != Underside::Kind::Box) {
    const Eigen::AlignedBox3d bounds = planeBounds(underside);
    return Eigen::AlignedBox2d(bounds.min().head<2>(), bounds.max().head<2>());
  }
  const Eigen::Matrix3d& axes = underside.plane_from_object.linear();
  const Eigen::Vector3d& half = underside.half_extents;
  const int down = mostUprightAxis(axes);
  const double below = axes(2, down) > 0.0 ? -1.0 : 1.0;  // the face whose normal points down
  const int a = (down + 1) % 3, b = (down + 2) % 3;
  const Eigen::Vector3d middle = underside.plane_from_object.translation() + below * half[down] * axes.col(down);
  Eigen::AlignedBox2d face;
  for (double sa : {-1.0, 1.0})
    for (double sb : {-1.0, 1.0}) face.extend((middle + sa * half[a] * axes.col(a) + sb * half[b] * axes.col(b)).head<2>());
  return face;
}

// A smooth chart (mesh_relief_chart.hpp) laid under an object posed at mesh_from_object: turned to
// the object's axis that lies most along it, its samples over the object's footprint.
void laySmoothChart(MeshChart& chart, const btCollisionShape& shape, const Eigen::Isometry3d& mesh_from_object,
                    int intervals, const FaceTexture* faces) {
  const Eigen::Vector3d n = chart.surface.mapping().plane_to_world.linear().col(2);
  int along = 0;
  for (int k = 1; k < 3; ++k) {
    const Eigen::Vector3d a = mesh_from_object.linear().col(k), best = mesh_from_object.linear().col(along);
    if ((a - a.dot(n) * n).norm() > (best - best.dot(n) * n).norm() + 1e-9) along = k;
  }
  alignChart(chart, mesh_from_object.linear().col(along));
  const std::optional<Underside> underside =
      undersideOf(shape, chart.surface.mapping().plane_to_world.inverse() * mesh_from_object);
  if (!underside) return;
  // A textured box's relief is read at its own texels (textured_box.hpp); by a pole, at the mesh's
  // relief's coarser texel where that is longer (MeshChart::least_cell_m).
  const double own = faces ? faces->tile_m / double(std::max(faces->map->width(), faces->map->height())) : 0.0;
  const double texel = faces ? std::max(chart.least_cell_m, own) : std::numeric_limits<double>::infinity();
  layGridUnder(chart, gridFootprint(*underside), intervals, texel);
}

// The object's motion as its rigid body has it (none for a collision object without a body).
BodyMotion motionOf(const btCollisionObject& object) {
  BodyMotion motion;
  motion.centre = toEigen(object.getWorldTransform().getOrigin());
  if (const btRigidBody* body = btRigidBody::upcast(&object)) {
    motion.centre = toEigen(body->getCenterOfMassPosition());
    motion.linear = toEigen(body->getLinearVelocity());
    motion.angular = toEigen(body->getAngularVelocity());
  }
  return motion;
}

// The object's motion as seen from the ground it meets (which moves where it is a box,
// box_ground.hpp): the velocity of each of its points less the ground's at the same place.
BodyMotion motionAgainst(const btCollisionObject& object, const btCollisionObject& ground) {
  BodyMotion motion = motionOf(object);
  const BodyMotion g = motionOf(ground);
  motion.linear -= g.linear + g.angular.cross(motion.centre - g.centre);
  motion.angular -= g.angular;
  return motion;
}

// What becomes of the points a manifold kept from earlier steps: Bullet's rule alone, or room made
// for every chosen point first (manifold_room.hpp).
enum class KeptPoints { AsBullet, RoomForChosen };

// Adds the chosen contacts (deepest first) to the result's manifold (relief_collision.hpp's
// convention). `object_relief`: a ball with a bump map, whose point of contact is on its recessed
// surface above the texel (where the pair's depth was measured), not where its smooth sphere
// faces -n. `more_manifolds` (a ball's basins, textured_ball_basins.hpp) take the points the
// result's own cannot hold: four at most, no two within the breaking threshold (below).
void addReliefContacts(std::span<const ReliefCandidate> chosen, const Underside& underside,
                       const tex::TexturedSurface& surface, const GroundBend& bend,
                       const Eigen::Isometry3d& world_from_plane, bool conforming, double threshold,
                       btManifoldResult* result, const BodyMotion* ball = nullptr, bool object_relief = false,
                       KeptPoints kept = KeptPoints::AsBullet,
                       std::span<btPersistentManifold* const> more_manifolds = {}) {
  constexpr std::size_t kMost = kMaxBallBasins, kMostManifolds = kMaxBallBasins / kMaxReliefContacts;
  const std::size_t manifolds = 1 + more_manifolds.size();
  assert(manifolds <= kMostManifolds && chosen.size() <= kMost);
  assert(kept == KeptPoints::AsBullet || manifolds == 1);
  // btManifoldResult::addContactPoint REPLACES a cached point whose point on the object lies
  // within the breaking threshold of the new one. The chosen points come deepest first, so a
  // later point that close to one in a manifold goes to the next manifold, or is skipped where
  // every manifold has one: the deeper one must win. (For a sphere every point with the same
  // normal maps to the same q = c - r n, see contactOnObject.)
  std::array<Eigen::Vector3d, kMost> added;
  std::array<std::size_t, kMost> added_to{};
  std::size_t added_count = 0;
  // The points Bullet will take (it drops those beyond the breaking threshold,
  // btManifoldResult::addContactPoint), added once all are known (manifold_room.hpp).
  std::array<btVector3, kMost> on_reliefs, normals, on_objects;
  std::array<btScalar, kMost> gaps;
  std::array<std::size_t, kMost> taken_to{};
  std::array<std::size_t, kMostManifolds> filled{};
  std::size_t taken = 0;
  for (const ReliefCandidate& c : chosen) {
    const Eigen::Vector3d n_world = world_from_plane.linear() * c.n_local;
    const Eigen::Vector3d lowest = c.p_surface + c.depth * Eigen::Vector3d::UnitZ();  // plane frame
    const Eigen::Vector3d q = object_relief ? lowest : contactOnObject(underside, lowest, c.n_local);
    // Signed distance of the contact point from the texel's tangent plane, along its normal:
    // for a box this is depth * n_z, for a round part the gap of the round surface itself (a
    // fringe texel of a capsule's end cap then reports the cap's real gap, not the fringe's).
    // On a CONVEX relief (a bump) the tangent plane of a texel away from the point of contact
    // lies above the relief and cuts into a round object cresting it, by about
    // (R + r) s^2 / (2 R^2) at distance s (R: the relief's curvature radius): measured 55 µm of
    // lift and +1.4 % energy for a 1 cm ball cresting a 1 mm bump, its escape speed 4 % low.
    // The relief's own height under the contact point (bilinear, one sample) is not fooled by
    // the curvature; the vertical gap there, projected on n, is used when it is the larger.
    // Flat reliefs give the same value both ways, concave spots keep the tangent-plane gap.
    const double gap_below_q = q.z() - surface.at(q.x(), q.y()).height_m - bend.height(q.x(), q.y());
    const double distance = conforming ? c.depth : std::max((q - c.p_surface).dot(c.n_local), gap_below_q * c.n_local.z());
    const Eigen::Vector3d on_object = world_from_plane * q;
    // A ball's further point still open while it moves onto it: an impact still to come, which
    // Bullet would take early (speculative_contacts.hpp).
    if (ball && &c != &chosen.front() && !keepFurtherContact(distance, approachSpeed(*ball, on_object, n_world))) continue;
    auto nearOneIn = [&](std::size_t m) {
      for (std::size_t a = 0; a < added_count; ++a)
        if (added_to[a] == m && (added[a] - on_object).squaredNorm() < threshold * threshold) return true;
      return false;
    };
    std::size_t to = 0;
    while (to < manifolds && (filled[to] == kMaxReliefContacts || nearOneIn(to))) ++to;
    if (to == manifolds) continue;
    added[added_count] = on_object, added_to[added_count++] = to;
    if (static_cast<btScalar>(distance) > static_cast<btScalar>(threshold)) continue;
    const Eigen::Vector3d on_relief = on_object - distance * n_world;
    on_reliefs[taken] = toBt(on_relief), normals[taken] = toBt(n_world), gaps[taken] = static_cast<btScalar>(distance);
    on_objects[taken] = on_reliefs[taken] + normals[taken] * gaps[taken];  // as Bullet finds it again
    taken_to[taken++] = to, ++filled[to];
  }
  if (kept == KeptPoints::RoomForChosen)
    makeRoomFor(*result->getPersistentManifold(), std::span(on_objects.data(), taken));
  btPersistentManifold* own = result->getPersistentManifold();
  for (std::size_t m = 0; m < manifolds; ++m) {
    if (filled[m] == 0) continue;
    result->setPersistentManifold(m == 0 ? own : more_manifolds[m - 1]);
    for (std::size_t k = 0; k < taken; ++k)
      if (taken_to[k] == m) result->addContactPoint(normals[k], on_reliefs[k], gaps[k]);
  }
  result->setPersistentManifold(own);
}

// Which group of a textured box's contacts a normal (plane frame) falls in: 0 within 6° of the
// plane's normal, else 1-4 by the quarter of the plane its tilt leans towards (centred on +x, +y,
// -x, -y). Contacts on walls that face each other land in different groups, so each group's four
// points hold the box from its own side (one manifold of four points chose the deepest and the
// most spread points, all on the walls facing one way, and the grooved block walked off them).
std::size_t normalGroup(const Eigen::Vector3d& n) {
  const double tilt = std::hypot(n.x(), n.y());
  if (tilt < 0.1) return 0;
  if (std::fabs(n.x()) >= std::fabs(n.y())) return n.x() > 0.0 ? 1 : 3;
  return n.y() > 0.0 ? 2 : 4;
}

// A ball with a bump map on the relief plane (textured_ball.hpp): the pair's depth rasterised
// over the plane's texels under it, its basins closest to closing (the deepest first: each the
// bottom of a basin in that depth, where the two surfaces' normals agree) located within their
// texels as a plain ball's (refineDeepest, on the pair's depth), their normals by the pair's rule, and the
// relief's own where it is much flatter than the ball there (pair_contact_normal.hpp), found
// afresh each step as a plain ball's are.
// On a mesh's chart (`bend` its smooth surface's, `boundary` where it stops) as on the plane.
// `settle_points`: every point refined until it settles (refineDeepest), for a smooth chart
// sampled coarser than the ball's texels (by a pole of the uv, mesh_relief_chart.hpp).
// `closing_within_m`: the gap below which basins past the fourth are kept (findBallBasins);
// `more_manifolds` (cleared): where the points the result's own cannot hold go.
// On flat ground (a plain plane's or a plain box face's smooth chart, a relief of one level under
// the ball; or smooth there, kSmoothReliefBend, read under each point), or a mesh chart's
// smoothly bent one (its bend known, no chart edge in reach), and
// with its texel grid (`grid`, PhysicsWorld::addTexturedSphere), the ball's own lowest points
// instead (ball_on_flat_ground.hpp).
void texturedBallCollision(const tex::TexturedSurface& surface, const GroundBend& bend, const ChartBoundary* boundary,
                           const Underside& underside, const FaceTexture& texture, const BallTexelGrid* grid,
                           double threshold, const Eigen::Isometry3d& world_from_plane, const BodyMotion& motion,
                           BallBasinHint& hint, double closing_within_m, btManifoldResult* result,
                           std::span<btPersistentManifold* const> more_manifolds, bool settle_points = false) {
  const GroundBend* bent = bend.flat() ? nullptr : &bend;
  std::array<ReliefCandidate, kMaxBallBasins> chosen{};
  // On flat or smoothly bent ground, the ball's own lowest points (ball_on_flat_ground.hpp). A
  // flat face's fit is rounding (1e-15 /m on a box's face), as for a textured box, and is read as
  // flat; a form not fitted says nothing.
  const double reach = (underside.plane_from_object.translation().head<2>() - bend.centre).norm() + underside.radius;
  const GroundBend* bent_in_reach = bend.flatWithin(reach, 1e-12) ? nullptr : &bend;
  if (grid && bend.known && !(boundary && boundary->count > 0)) {
    if (const std::optional<FlatGround> ground = flatGround(surface, underside, threshold, bent_in_reach)) {
      const std::size_t n = ballOnFlatGround(*grid, surface, underside, ground->height_m, bent_in_reach, threshold,
                                             closing_within_m, hint, chosen, ground->read_relief);
      addReliefContacts(std::span(chosen.data(), n), underside, surface, bend, world_from_plane, false, threshold, result,
                        &motion, true, KeptPoints::AsBullet, more_manifolds);
      return;
    }
  }
  thread_local std::vector<ReliefCandidate> candidates;
  candidates.clear();
  // The basins closest to closing, deepest first (selectShallowestBasins; the ball's texture read
  // for its depth under the texels, only as far out as they can lie: textured_ball_basins.hpp),
  // each refined to its bottom between the texels: a bumpy ball's supports are its bump tips, and
  // the next tip to touch must be among them before it touches. Its normal is read at the points kept.
  const BallBasins basins =
      findBallBasins(surface, underside, texture, threshold, closing_within_m, bent, boundary, hint, candidates);
  const std::size_t n = basins.count;
  const TexturedObjectSurface ball(underside, texture);
  for (std::size_t k = 0; k < n; ++k) {
    ReliefCandidate c = candidates[basins.picked[k]];
    withNormals(surface, bent, &ball, c);
    chosen[k] = refineDeepest(surface, underside, c, bent, &texture, settle_points);
  }
  smootherSurfaceNormals(surface, bent, ball, std::span(chosen.data(), n));
  flatterReliefNormals(surface, bent, ball, std::span(chosen.data(), n));
  addReliefContacts(std::span(chosen.data(), n), underside, surface, bend, world_from_plane, false, threshold, result,
                    &motion, true, KeptPoints::AsBullet, more_manifolds);
}

}  // namespace

void ReliefCollisionAlgorithm::texturedBoxCollision(const btCollisionObjectWrapper& object,
                                                    const btCollisionObjectWrapper& relief, const tex::TexturedSurface& surface,
                                                    const GroundBend& bend, const Underside& underside,
                                                    const FaceTexture& faces, const ChartBoundary* boundary,
                                                    double threshold, const Eigen::Isometry3d& world_from_plane,
                                                    int chart, btManifoldResult* result) {
  // Reused between steps so a resting box costs no allocation per step.
  thread_local std::vector<ReliefCandidate> candidates, group;
  thread_local std::vector<std::size_t> group_index, taken;
  thread_local std::vector<std::uint8_t> group_of;  // each candidate's normal group, read once
  candidates.clear();
  taken.clear();
  const RasterStats raster = rasterizeRelief(surface, underside, threshold, candidates, &faces, bend.flat() ? nullptr : &bend,
                                              true, boundary);
  dropPastBoundary(boundary, candidates);
  group_of.resize(candidates.size());
  for (std::size_t k = 0; k < candidates.size(); ++k) group_of[k] = std::uint8_t(normalGroup(candidates[k].n_local));
  const TexturedObjectSurface box_surface(underside, faces);
  // Ground flat under the whole footprint: no crease within reach, and a bend that is rounding (a
  // flat face's fit rises 1e-15 /m; a picometre over the box is nothing a relief stores).
  const double reach = (underside.plane_from_object.translation().head<2>() - bend.centre).norm() + underside.half_extents.norm();
  const bool flat_ground = bend.flatWithin(reach, 1e-12) && !(boundary && boundary->count > 0);
  // What the two reliefs' stored depths can resolve (a smooth chart stores none).
  const double depth_step = isSmoothChart(surface) ? faces.map->depthStep()
                                                   : std::max(surface.map().depthStep(), faces.map->depthStep());
  for (std::size_t g = 0; g < kNormalGroups; ++g) {
    result->setPersistentManifold(groupManifold(chart, g, object.getCollisionObject(), relief.getCollisionObject()));
    group.clear();
    group_index.clear();
    for (std::size_t k = 0; k < candidates.size(); ++k)
      if (group_of[k] == g) group.push_back(candidates[k]), group_index.push_back(k);
    std::array<std::size_t, kMaxReliefContacts> picked{};
    // Level contacts on flat ground within the chart: the lowest point of each quarter of the
    // footprint (contact_selection.hpp), as a plain box's.
    const bool level = g == 0 && flat_ground;
    const std::size_t n = level ? selectBoxQuarterContacts(group, quartersUnder(underside, depth_step), picked)
                                : selectReliefContacts(group, picked);
    for (std::size_t k = 0; k < n; ++k) picked[k] = group_index[picked[k]];
    // Each to the bottom of its basin in the pair's depth, where the two surfaces' normals agree.
    if (!level) snapToBasins(candidates, raster.stride_i, raster.stride_j, std::span(picked.data(), n));
    // A basin another group's point went to already holds a contact.
    std::array<ReliefCandidate, kMaxReliefContacts> chosen{};
    std::size_t count = 0;
    for (std::size_t k = 0; k < n; ++k) {
      if (std::find(taken.begin(), taken.end(), picked[k]) != taken.end()) continue;
      taken.push_back(picked[k]);
      chosen[count++] = candidates[picked[k]];
    }
    // A crest pressing on the other body's wall: the wall's normal (pair_contact_normal.hpp).
    smootherSurfaceNormals(surface, bend.flat() ? nullptr : &bend, box_surface, std::span(chosen.data(), count));
    addReliefContacts(std::span(chosen.data(), count), underside, surface, bend, world_from_plane, false, threshold, result,
                      nullptr, false, level ? KeptPoints::RoomForChosen : KeptPoints::AsBullet);
    // The points of earlier steps stay, each replaced by a new one within the breaking threshold
    // of it (keeping its impulse to start the solver from) or dropped once its gap or slide
    // exceeds that threshold; Bullet keeps the four that span the most area (the level points on
    // flat ground: every chosen one first, manifold_room.hpp). Cleared every step
    // as the other shapes' are (a rolling ball's cached points inject energy; a box does not
    // roll), the deepest texels, chosen afresh, stayed 10-60 µm deep, and the grooved block
    // crept up the plane's walls under 0.58 of its weight at 128 texels, against 0.78 kept.
    result->refreshContactPoints();
  }
  result->setPersistentManifold(manifoldFor(object.getCollisionObject(), relief.getCollisionObject()));
}

btPersistentManifold* ReliefCollisionAlgorithm::groupManifold(int chart, std::size_t g, const btCollisionObject* object,
                                                             const btCollisionObject* relief) {
  if (chart == kUnder && g == 0) return manifoldFor(object, relief);
  btPersistentManifold*& m = chart == kUnder ? groups_[g - 1] : surfaces_->slots[std::size_t(chart)].groups[g];
  if (!m) m = m_dispatcher->getNewManifold(object, relief);
  return m;
}

std::array<btPersistentManifold*, ReliefCollisionAlgorithm::kBallMoreManifolds>
ReliefCollisionAlgorithm::ballManifolds(int chart, const btCollisionObject* object, const btCollisionObject* relief) {
  std::array<btPersistentManifold*, kBallMoreManifolds> more{};
  for (std::size_t g = 0; g < more.size(); ++g) {
    more[g] = groupManifold(chart, g + 1, object, relief);
    more[g]->clearManifold();
  }
  return more;
}

void ReliefCollisionAlgorithm::clearGroupManifolds() {
  for (btPersistentManifold* m : groups_)
    if (m) m->clearManifold();
}

void ReliefCollisionAlgorithm::clearSlot(int slot) {
  SurfaceSlot& s = surfaces_->slots[std::size_t(slot)];
  for (btPersistentManifold* m : s.groups)
    if (m) m->clearManifold();
  s.held = false;
  s.ball_hint = {};
}

int ReliefCollisionAlgorithm::surfaceSlot(const Eigen::Vector3d& normal, std::uint32_t taken) {
  if (!surfaces_) surfaces_ = std::make_unique<SurfaceSlots>();
  const double same = std::cos(kCreaseFromChartDeg * std::numbers::pi / 180.0);
  int free_slot = kUnder;
  for (std::size_t k = 0; k < surfaces_->slots.size(); ++k) {
    if (taken & (1u << k)) continue;
    const SurfaceSlot& s = surfaces_->slots[k];
    // Not across a crease from the surface it held: the same surface.
    if (s.held && s.normal.dot(normal) >= same) return int(k);
    if (!s.held && free_slot == kUnder) free_slot = int(k);
  }
  if (free_slot == kUnder)  // every slot held a surface last step: take one this step has not
    for (std::size_t k = 0; k < surfaces_->slots.size() && free_slot == kUnder; ++k)
      if (!(taken & (1u << k))) free_slot = int(k);
  if (free_slot != kUnder) {
    clearSlot(free_slot);
    surfaces_->slots[std::size_t(free_slot)].normal = normal;
  }
  return free_slot;
}

ReliefCollisionAlgorithm::~ReliefCollisionAlgorithm() {
  for (btPersistentManifold* m : groups_)
    if (m) m_dispatcher->releaseManifold(m);
  if (surfaces_)
    for (SurfaceSlot& s : surfaces_->slots)
      for (btPersistentManifold* m : s.groups)
        if (m) m_dispatcher->releaseManifold(m);
}

void ReliefCollisionAlgorithm::getAllContactManifolds(btManifoldArray& manifolds) { chartManifolds(manifolds); }

void ReliefCollisionAlgorithm::slotManifolds(int slot, btManifoldArray& manifolds) {
  if (slot == kUnder) {
    ManifoldAlgorithm::getAllContactManifolds(manifolds);
    for (btPersistentManifold* m : groups_)
      if (m) manifolds.push_back(m);
    return;
  }
  for (btPersistentManifold* m : surfaces_->slots[std::size_t(slot)].groups)
    if (m) manifolds.push_back(m);
}

void ReliefCollisionAlgorithm::chartManifolds(btManifoldArray& manifolds) {
  slotManifolds(kUnder, manifolds);
  if (surfaces_)
    for (std::size_t k = 0; k < surfaces_->slots.size(); ++k) slotManifolds(int(k), manifolds);
}

ChartBoundary ReliefCollisionAlgorithm::chartCollision(const btCollisionObjectWrapper& object,
                                                       const btCollisionObjectWrapper& mesh, const MeshRelief& relief,
                                                       const btConcaveShape& triangles_shape, const FaceTexture* faces,
                                                       const MeshChart& chart, int slot, MeshGround ground,
                                                       const Eigen::AlignedBox3d& reach, double threshold,
                                                       btManifoldResult* result) {
  const Eigen::Isometry3d world_from_mesh = toEigen(mesh.getWorldTransform());
  const Eigen::Isometry3d world_from_object = toEigen(object.getWorldTransform());
  const Eigen::Isometry3d& mesh_from_chart = chart.surface.mapping().plane_to_world;
  const Eigen::Isometry3d world_from_chart = world_from_mesh * mesh_from_chart;
  // Where the chart stops: faces across a crease within the object's reach (chart_boundary.hpp).
  const mesh::TexturedMesh& triangles = *relief.mesh.mesh;
  const mesh::Triangle& foot = triangles.triangles[chart.triangle];
  const Eigen::Vector3d foot_middle =
      (triangles.positions[foot[0]] + triangles.positions[foot[1]] + triangles.positions[foot[2]]) / 3.0;
  const ChartBoundary boundary =
      ground == MeshGround::Ball
          ? ChartBoundary{}
          : chartBoundary(triangles_shape, relief.mesh, mesh_from_chart, (mesh_from_chart.inverse() * foot_middle).head<2>(),
                          reach, world_from_mesh.inverse() * world_from_object.translation(),
                          reachOf(*object.getCollisionShape()) + threshold, chart.side);
  const std::optional<Underside> underside =
      undersideOf(*object.getCollisionShape(), world_from_chart.inverse() * world_from_object);
  if (!underside) return boundary;
  if (const FaceTexture* ball = ballTextureOf(*object.getCollisionShape())) {
    // A ball with a bump map: its points afresh each step, as on the plane.
    btPersistentManifold* manifold = groupManifold(slot, 0, object.getCollisionObject(), mesh.getCollisionObject());
    result->setPersistentManifold(manifold);
    manifold->clearManifold();
    BallBasinHint& hint = slot == kUnder ? ball_hint_ : surfaces_->slots[std::size_t(slot)].ball_hint;
    texturedBallCollision(chart.surface, chart.bend, &boundary, *underside, *ball,
                          ballTexelGridOf(*object.getCollisionShape()), threshold, world_from_chart,
                          motionAgainst(*object.getCollisionObject(), *mesh.getCollisionObject()), hint,
                          closable_gap_m_, result,
                          ballManifolds(slot, object.getCollisionObject(), mesh.getCollisionObject()),
                          chart.least_cell_m > 0.0);
  } else if (faces) {
    texturedBoxCollision(object, mesh, chart.surface, chart.bend, *underside, *faces, &boundary, threshold,
                         world_from_chart, slot, result);
  } else {
    // An untextured object: the plane's rule on the chart (points afresh each step, as there).
    btPersistentManifold* manifold = groupManifold(slot, 0, object.getCollisionObject(), mesh.getCollisionObject());
    result->setPersistentManifold(manifold);
    const bool on_end_face = standsOnEndFace(*underside);
    if (!on_end_face) manifold->clearManifold();
    plainObjectCollision(chart.surface, chart.bend, *underside, on_end_face, nullptr, &boundary, threshold,
                         world_from_chart, motionAgainst(*object.getCollisionObject(), *mesh.getCollisionObject()),
                         result);
  }
  // Each point names the triangle under it on the mesh's side, as Bullet's own points do (the
  // physics client reads a contact's texel through it).
  btManifoldArray manifolds;
  slotManifolds(slot, manifolds);
  const Eigen::Isometry3d mesh_from_world = world_from_mesh.inverse();
  for (int m = 0; m < manifolds.size(); ++m) {
    for (int k = 0; k < manifolds[m]->getNumContacts(); ++k) {
      btManifoldPoint& p = manifolds[m]->getContactPoint(k);
      p.m_partId1 = 0;
      p.m_index1 = int(triangleUnder(relief, mesh_from_world * toEigen(p.getPositionWorldOnB()), chart.triangle));
    }
  }
  return boundary;
}

void ReliefCollisionAlgorithm::meshCollision(const btCollisionObjectWrapper& object, const btCollisionObjectWrapper& mesh,
                                             const MeshRelief& relief, const btConcaveShape& triangles,
                                             const FaceTexture* faces, MeshGround ground,
                                             btManifoldResult* result) {
  const bool object_ground = ground != MeshGround::Scene;
  btPersistentManifold* manifold = manifoldFor(object.getCollisionObject(), mesh.getCollisionObject());
  result->setPersistentManifold(manifold);
  const Eigen::Isometry3d world_from_mesh = toEigen(mesh.getWorldTransform());
  const Eigen::Isometry3d mesh_from_object = world_from_mesh.inverse() * toEigen(object.getWorldTransform());
  const btCollisionShape& shape = *object.getCollisionShape();
  // Where the chart is laid: under the object's centre, or, for a cylinder against a box or a
  // ball, under its axis's point nearest their centre. An upright cylinder beside a box's side
  // face (the pen's height, its centre far over the box) had its chart laid at the top edge
  // nearest its centre and met the side on a chart across that crease: the block it pushed slid
  // off along the face's upright grooves and rose at 0.018 m/s.
  const Eigen::Vector3d centre = object_ground ? rodPointNearestOrigin(shape, mesh_from_object) : mesh_from_object.translation();
  const double reach_m = reachOf(shape) + (centre - mesh_from_object.translation()).norm();
  std::uint32_t held = 0;  // the slots of surfaces across creases met this step
  MeshChart chart;
  // A smooth chart's grid is laid at the object's own texels where it has a texture.
  const FaceTexture* texture = faces ? faces : ballTextureOf(shape);
  const double threshold = double(manifold->getContactBreakingThreshold());
  btVector3 aabb_min, aabb_max;
  shape.getAabb(toBt(mesh_from_object), aabb_min, aabb_max);
  const Eigen::Vector3d margin = Eigen::Vector3d::Constant(threshold);
  const Eigen::AlignedBox3d reach(toEigen(aabb_min) - margin, toEigen(aabb_max) + margin);
  // Bullet keeps a pair while their bounds, each widened by its breaking threshold (2 cm), meet;
  // an object wholly beyond the mesh's own bounds touches nothing of it. (The chart under it would
  // be laid on the nearest face and run on past that face's edge, the faces across which lie out
  // of the object's reach: a marble rolling off a box's edge rode on at its height for 0.5 s.)
  triangles.getAabb(btTransform::getIdentity(), aabb_min, aabb_max);
  const bool within = reach.intersects(Eigen::AlignedBox3d(toEigen(aabb_min), toEigen(aabb_max)));
  // The walk to the foot from last step's, while that is still within reach and faces the object;
  // else from the nearest triangle within reach (none: nothing to meet).
  if (within) foot_triangle_ = footToWalkFrom(relief, triangles, centre, reach, foot_triangle_);
  if (within && foot_triangle_ != mesh::kNoNeighbour && chartUnder(relief, centre, reach_m, foot_triangle_, by_pole_, chart)) {
    if (chart.smooth) laySmoothChart(chart, shape, mesh_from_object, relief.grid_intervals, texture);
    const ChartBoundary boundary =
        chartCollision(object, mesh, relief, triangles, faces, chart, kUnder, ground, reach, threshold, result);
    // Each surface across a crease within reach, on a chart of its own at its point nearest the
    // object's centre, cut at its own creases (the chart under the object's surface among them).
    for (std::size_t k = 0; k < boundary.surface_count; ++k) {
      const BeyondSurface& beyond = boundary.surfaces[k];
      MeshChart across;
      if (!chartOnFace(relief, centre, reach_m, beyond.nearest_triangle, chart.side, across)) continue;
      const int slot = surfaceSlot(beyond.normal, held);
      if (slot == kUnder) continue;
      held |= 1u << std::size_t(slot);
      if (across.smooth) laySmoothChart(across, shape, mesh_from_object, relief.grid_intervals, texture);
      chartCollision(object, mesh, relief, triangles, faces, across, slot, ground, reach, threshold, result);
    }
  } else {
    // Beyond the mesh, or behind the winding: nothing textured to meet (mesh_relief_chart.hpp).
    manifold->clearManifold();
    clearGroupManifolds();
  }
  if (surfaces_)
    for (std::size_t k = 0; k < surfaces_->slots.size(); ++k) {
      if (held & (1u << k)) {
        surfaces_->slots[k].held = true;
      } else if (surfaces_->slots[k].held) {
        clearSlot(int(k));
      }
    }
  result->setPersistentManifold(manifold);
}

void ReliefCollisionAlgorithm::processCollision(const btCollisionObjectWrapper* body0,
                                                const btCollisionObjectWrapper* body1, const btDispatcherInfo& info,
                                                btManifoldResult* result) {
  closable_gap_m_ = closableGap(double(info.m_timeStep));
  const btCollisionObjectWrapper* object = swapped_ ? body1 : body0;
  const btCollisionObjectWrapper* relief = swapped_ ? body0 : body1;
  const btCollisionShape& ground = *relief->getCollisionShape();
  if (const MeshRelief* mesh = meshReliefOf(ground)) {
    meshCollision(*object, *relief, *mesh, static_cast<const btConcaveShape&>(ground),
                  faceTextureOf(*object->getCollisionShape()), MeshGround::Scene, result);
    return;
  }
  if (ground.getShapeType() == STATIC_PLANE_PROXYTYPE) {
    plainPlaneCollision(*object, *relief, result);
    return;
  }
  const FaceTexture* ground_ball = ballTextureOf(ground);
  if (ground.getShapeType() == BOX_SHAPE_PROXYTYPE || ground_ball) {
    // A box as a mesh of its faces, a ball with a bump map as its cube-sphere (box_ground.hpp).
    if (!shared_ground_ && !object_ground_)
      object_ground_ = ground_ball ? ballGround(double(static_cast<const btSphereShape&>(ground).getRadius()), *ground_ball)
                                   : boxGround(toEigen(static_cast<const btBoxShape&>(ground).getHalfExtentsWithMargin()),
                                               faceTextureOf(ground));
    const ObjectGround& object_ground = shared_ground_ ? *shared_ground_ : *object_ground_;
    meshCollision(*object, *relief, object_ground.relief(), object_ground.triangles(),
                  faceTextureOf(*object->getCollisionShape()), ground_ball ? MeshGround::Ball : MeshGround::Box,
                  result);
    return;
  }
  btPersistentManifold* manifold = manifoldFor(object->getCollisionObject(), relief->getCollisionObject());
  result->setPersistentManifold(manifold);
  const auto& plane = static_cast<const ReliefPlaneShape&>(*relief->getCollisionShape());
  const Eigen::Isometry3d world_from_plane = toEigen(relief->getWorldTransform());
  const Eigen::Isometry3d world_from_object = toEigen(object->getWorldTransform());
  const std::optional<Underside> underside =
      undersideOf(*object->getCollisionShape(), world_from_plane.inverse() * world_from_object);
  // A textured box (texturedBoxCollision) and a cylinder standing on an end face
  // (end_face_contacts.hpp) keep their points between steps; everything else starts afresh
  // (relief_collision.hpp).
  const FaceTexture* box_faces = faceTextureOf(*object->getCollisionShape());
  const bool on_end_face = underside && standsOnEndFace(*underside);
  if (!box_faces && !on_end_face) manifold->clearManifold();
  if (!underside) return;

  const double threshold = double(manifold->getContactBreakingThreshold());
  if (const FaceTexture* ball = ballTextureOf(*object->getCollisionShape())) {
    clearGroupManifolds();
    texturedBallCollision(plane.surface(), GroundBend{}, nullptr, *underside, *ball,
                          ballTexelGridOf(*object->getCollisionShape()), threshold, world_from_plane,
                          motionOf(*object->getCollisionObject()), ball_hint_, closable_gap_m_, result,
                          ballManifolds(kUnder, object->getCollisionObject(), relief->getCollisionObject()));
    return;
  }
  // A box with a relief on its faces (textured_box.hpp): its own rule, one manifold per group of
  // normals.
  if (box_faces) {
    texturedBoxCollision(*object, *relief, plane.surface(), GroundBend{}, *underside, *box_faces, nullptr, threshold,
                         world_from_plane, kUnder, result);
    return;
  }
  clearGroupManifolds();
  plainObjectCollision(plane.surface(), GroundBend{}, *underside, on_end_face, &plane.levelRuns(), nullptr, threshold,
                       world_from_plane, motionOf(*object->getCollisionObject()), result);
}

void ReliefCollisionAlgorithm::plainPlaneCollision(const btCollisionObjectWrapper& object,
                                                   const btCollisionObjectWrapper& plane, btManifoldResult* result) {
  btPersistentManifold* manifold = manifoldFor(object.getCollisionObject(), plane.getCollisionObject());
  result->setPersistentManifold(manifold);
  const btCollisionShape& shape = *object.getCollisionShape();
  const Eigen::Isometry3d world_from_plane = toEigen(plane.getWorldTransform());
  const Eigen::Isometry3d plane_from_object = world_from_plane.inverse() * toEigen(object.getWorldTransform());
  // The chart's origin at the foot of the object's centre, as a mesh's is (the plane reaches on
  // for ever, so no boundary), laid as a plain box's face is under it: turned to the object, its
  // samples at the object's own texels over its footprint.
  MeshChart chart = flatSmoothChart(Eigen::Isometry3d(
      Eigen::Translation3d(plane_from_object.translation().x(), plane_from_object.translation().y(), 0.0)));
  const FaceTexture* faces = faceTextureOf(shape);
  laySmoothChart(chart, shape, plane_from_object, kSmoothChartIntervals, faces ? faces : ballTextureOf(shape));
  const Eigen::Isometry3d world_from_chart = world_from_plane * chart.surface.mapping().plane_to_world;
  const std::optional<Underside> underside = undersideOf(shape, world_from_chart.inverse() * toEigen(object.getWorldTransform()));
  const double threshold = double(manifold->getContactBreakingThreshold());
  if (!underside) {
    manifold->clearManifold();
    clearGroupManifolds();
    return;
  }
  if (faces) {
    texturedBoxCollision(object, plane, chart.surface, chart.bend, *underside, *faces, nullptr, threshold,
                         world_from_chart, kUnder, result);
    return;
  }
  // A ball with a bump map (the create function takes no other shape): its points afresh each step.
  manifold->clearManifold();
  clearGroupManifolds();
  texturedBallCollision(chart.surface, chart.bend, nullptr, *underside, *ballTextureOf(shape), ballTexelGridOf(shape),
                        threshold, world_from_chart, motionOf(*object.getCollisionObject()), ball_hint_, closable_gap_m_,
                        result, ballManifolds(kUnder, object.getCollisionObject(), plane.getCollisionObject()));
}

void ReliefCollisionAlgorithm::plainObjectCollision(const tex::TexturedSurface& surface, const GroundBend& bend,
                                                    const Underside& underside, bool on_end_face,
                                                    const ReliefLevelRuns* level_runs, const ChartBoundary* boundary,
                                                    double threshold, const Eigen::Isometry3d& world_from_plane,
                                                    const BodyMotion& motion, btManifoldResult* result) {
  const GroundBend* bent = bend.flat() ? nullptr : &bend;
  ChosenReliefContacts chosen;
  bool conforming = false;
  const bool bounded = boundary && boundary->count > 0;
  const bool rod = underside.kind == Underside::Kind::Capsule || underside.kind == Underside::Kind::Cylinder;
  if (underside.kind == Underside::Kind::Box && !bent && !bounded &&
      boxReliefContacts(surface, underside, threshold, chosen, level_runs)) {
    // A box rests on the lowest point of each quarter of its footprint (the tops of the bumps
    // under it; a flat relief's corners). Not refined: its faces are flat. The rule of the branch
    // below, computed row by row (box_relief_contacts.hpp); on flat ground only.
  } else {
    // Reused between steps so a resting object costs no allocation per step.
    thread_local std::vector<ReliefCandidate> candidates;
    candidates.clear();
    // Normals are read for the contacts kept only (below).
    const RasterStats raster = rasterizeRelief(surface, underside, threshold, candidates, nullptr, bent, false, boundary);
    dropPastBoundary(boundary, candidates);
    // Refined within its texel (relief_raster.hpp), but kept on the chart: a box tilted over a
    // slab's edge has its deepest point on flat ground at its far edge, over the air past the crease,
    // and a block tipping off the edge was held there and thrown back.
    auto refine = [&](const ReliefCandidate& c) {
      const ReliefCandidate refined = refineDeepest(surface, underside, c, bent);
      return offChart(boundary, refined) ? c : refined;
    };
    // A ball in a relief of its own curvature: contacts by position, one measure
    // (conforming_contact.hpp). Otherwise the deepest and the spread points.
    std::array<std::size_t, kMaxReliefContacts> picked{};
    std::size_t n = 0;
    bool lying_rod = false;
    conforming = underside.kind == Underside::Kind::Sphere && raster.stride_i == 1 && raster.stride_j == 1 && !candidates.empty() &&
                 (n = selectConformingContacts(surface, underside, candidates, picked)) > 0;
    const Eigen::Vector2d texel = surface.mapping().texelSize(surface.map()).cwiseAbs();
    // A box rests on the lowest of each quarter of its footprint (selectBoxQuarterContacts), as the
    // row-by-row path above computes it; a smooth chart's box keeps the spread rule, refined on
    // the bend, and a huge box's footprint visited with a stride the spread rule.
    const bool box_quarters = underside.kind == Underside::Kind::Box && !isSmoothChart(surface) &&
                              raster.stride_i == 1 && raster.stride_j == 1 && !candidates.empty();
    if (on_end_face) {
      n = selectEndFaceContacts(candidates, underside, texel.maxCoeff(), raster.stride_i, raster.stride_j, picked);
    } else if (rod) {
      // Along its lines of contact, each end and each side (contact_selection.hpp); a rod standing
      // steeply takes the general rule.
      const Eigen::Vector3d axis = underside.plane_from_object.linear().col(underside.axis);
      const double band = 1.5 * std::max(texel.x() * double(raster.stride_i), texel.y() * double(raster.stride_j));
      const bool cylinder = underside.kind == Underside::Kind::Cylinder;
      n = selectLyingRodContacts(candidates, underside.plane_from_object.translation().head<2>(), axis.head<2>(), band,
                                 picked, cylinder, cylinder ? 0.0 : underside.half_length);
      lying_rod = n > 0;
      if (!lying_rod) n = selectReliefContacts(candidates, picked);
    } else if (box_quarters) {
      n = selectBoxQuarterContacts(candidates, quartersUnder(underside, surface.map().depthStep()), picked);
    } else if (!conforming) {
      n = selectReliefContacts(candidates, picked);
    }
    // Round objects roll on their contacts: locate them within their texels (relief_raster.hpp).
    // A sphere touches at the bottoms of basins (contact_selection.hpp); a lying rod on its lines
    // of contact, each refined across its line; a standing cylinder's face is flat
    // (end_face_contacts.hpp), so only its deepest point is refined.
    if (conforming) {
      // Texel centres with their own normals, already measured: nothing to refine or snap.
    } else if (n > 0 && underside.kind == Underside::Kind::Sphere) {
      const std::array<std::size_t, kMaxReliefContacts> spread = picked;
      snapToBasins(candidates, raster.stride_i, raster.stride_j, std::span(picked.data(), n));
      for (std::size_t k = 0; k < n; ++k)
        if (k == 0 || picked[k] != spread[k]) candidates[picked[k]] = refine(candidates[picked[k]]);
    } else if (box_quarters) {
      // Each the lowest of its quarter already: nothing to snap; its faces are flat.
    } else if (n > 0 && underside.kind == Underside::Kind::Box) {
      // A box whose footprint is visited with a stride (a huge box): the same rule on the texels visited.
      // On a smooth chart the gap is the bend's quadratic alone, and a box's spread points stand
      // symmetrically about its line of contact on a cylinder: each spread point's basin lies as near
      // another's as its own, the nearest-point claim refused them all, and the box hung on its one
      // deepest point at one end every few steps (losing a third of its swing's energy and taking it
      // back). There any basin no earlier point took is claimed.
      const bool smooth = isSmoothChart(surface);
      snapToBasins(candidates, raster.stride_i, raster.stride_j, std::span(picked.data(), n),
                   smooth ? BasinClaim::SameTexel : BasinClaim::NearestPoint);
      // On a smooth chart each point is then taken to where the face meets the curved ground between
      // the samples, so a box rocking on a cylinder rolls on the line it touches rather than from
      // sample to sample.
      if (smooth)
        for (std::size_t k = 0; k < n; ++k) candidates[picked[k]] = refine(candidates[picked[k]]);
    } else if (lying_rod) {
      for (std::size_t k = 0; k < n; ++k) candidates[picked[k]] = refine(candidates[picked[k]]);
    } else if (n > 0) {
      candidates[picked[0]] = refine(candidates[picked[0]]);
    }
    // A refined point carries the relief's normal where it lies; the others their texel's.
    for (std::size_t k = 0; k < n; ++k) {
      chosen.contacts[k] = candidates[picked[k]];
      if (!hasNormal(chosen.contacts[k])) withNormals(surface, bent, nullptr, chosen.contacts[k]);
    }
    chosen.count = n;
  }
  // A ball or a box none of whose texel centres is within the threshold may still touch the
  // relief between them (texels coarse against it, relief_raster.hpp).
  if (chosen.count == 0 && !bounded && underside.kind == Underside::Kind::Sphere) {
    if (const std::optional<ReliefCandidate> under = deepestBetweenTexelCentres(surface, underside, bent, threshold)) {
      chosen.contacts[0] = *under;
      chosen.count = 1;
    }
  } else if (!bounded && underside.kind == Underside::Kind::Box &&
             (chosen.count == 0 || (!isSmoothChart(surface) && boxUnderTwoTexelsAcross(surface, underside)))) {
    // Too few centres under the box to stand on: its corners (relief_raster.hpp).
    const std::array<ReliefCandidate, kMaxReliefContacts> centres = chosen.contacts;
    chosen.count = boxCornerContacts(surface, underside, bent, threshold, std::span(centres.data(), chosen.count),
                                     chosen.contacts);
  }

  // A box's face resting on a crease of the relief takes the face's normal (crease_contact.hpp);
  // a rod's side on a mesh's convex edge, the rod's (edge_contact.hpp).
  if (underside.kind == Underside::Kind::Box) faceNormalsOnCreases(surface, underside, chosen);
  if (rod && !on_end_face && bounded)
    rodNormalsAtConvexEdges(underside, *boundary, 1.5 * surface.mapping().texelSize(surface.map()).cwiseAbs().maxCoeff(),
                            chosen);
  // A ball's further points are left out while it moves onto them still open; a ball in a
  // conforming cap keeps its ring (speculative_contacts.hpp).
  const bool ball = underside.kind == Underside::Kind::Sphere && !conforming;
  addReliefContacts(std::span(chosen.contacts.data(), chosen.count), underside, surface, bend,
                    world_from_plane, conforming, threshold, result, ball ? &motion : nullptr);
  // Kept points follow the body and are dropped once they separate or slide beyond the
  // threshold, as in Bullet's own algorithms (kept without this, stale points stayed).
  if (on_end_face) result->refreshContactPoints();
}

namespace {

// The shapes that meet a relief mesh on its chart; a ball only with a bump map of its own (a plain
// ball keeps Bullet's points, lifted).
constexpr int kChartShapes[] = {BOX_SHAPE_PROXYTYPE, CAPSULE_SHAPE_PROXYTYPE, CYLINDER_SHAPE_PROXYTYPE,
                                SPHERE_SHAPE_PROXYTYPE};

}  // namespace

bool reliefTakesMeshPair(const btCollisionShape& object, const btCollisionShape& mesh) {
  if (meshReliefOf(mesh) == nullptr) return false;
  if (object.getShapeType() == SPHERE_SHAPE_PROXYTYPE) return ballTextureOf(object) != nullptr;
  return std::find(std::begin(kChartShapes), std::end(kChartShapes), object.getShapeType()) != std::end(kChartShapes);
}

namespace {

// Box, capsule, cylinder or ball with a bump map against a triangle mesh: ours on a relief-textured
// mesh (reliefTakesMeshPair), Bullet's convex-concave algorithm (its default for the pair)
// otherwise. Decided when Bullet makes the pair's algorithm; a shape's texture is fixed when it is
// added.
struct MeshPairCreateFunc : btCollisionAlgorithmCreateFunc {
  explicit MeshPairCreateFunc(bool swapped) { m_swapped = swapped; }
  btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                 const btCollisionObjectWrapper* body0,
                                                 const btCollisionObjectWrapper* body1) override {
    const btCollisionObjectWrapper* object = m_swapped ? body1 : body0;
    const btCollisionObjectWrapper* mesh = m_swapped ? body0 : body1;
    if (reliefTakesMeshPair(*object->getCollisionShape(), *mesh->getCollisionShape()))
      return ManifoldAlgorithm::create<ReliefCollisionAlgorithm>(ci, body0, body1, m_swapped);
    return m_swapped ? bullet_swapped.CreateCollisionAlgorithm(ci, body0, body1)
                     : bullet_direct.CreateCollisionAlgorithm(ci, body0, body1);
  }
  btConvexConcaveCollisionAlgorithm::CreateFunc bullet_direct;
  btConvexConcaveCollisionAlgorithm::SwappedCreateFunc bullet_swapped;
};

}  // namespace

void registerReliefCollision(btCollisionDispatcher& dispatcher) {
  static ReliefCollisionAlgorithm::CreateFunc direct(false);
  static ReliefCollisionAlgorithm::CreateFunc swapped(true);
  for (int type : {SPHERE_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE, CAPSULE_SHAPE_PROXYTYPE, CYLINDER_SHAPE_PROXYTYPE}) {
    dispatcher.registerCollisionCreateFunc(type, CUSTOM_CONCAVE_SHAPE_TYPE, &direct);
    dispatcher.registerCollisionCreateFunc(CUSTOM_CONCAVE_SHAPE_TYPE, type, &swapped);
  }
  static MeshPairCreateFunc mesh_direct(false);
  static MeshPairCreateFunc mesh_swapped(true);
  for (int type : kChartShapes) {
    dispatcher.registerCollisionCreateFunc(type, TRIANGLE_MESH_SHAPE_PROXYTYPE, &mesh_direct);
    dispatcher.registerCollisionCreateFunc(TRIANGLE_MESH_SHAPE_PROXYTYPE, type, &mesh_swapped);
  }
}

}  // namespace thx::phys
