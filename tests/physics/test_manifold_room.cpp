// Room in a kept manifold for every point chosen this step (clients/physics/manifold_room.hpp).
#include <gtest/gtest.h>

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <array>
#include <vector>

#include "clients/physics/manifold_room.hpp"

namespace thx::phys::test::test_manifold_room {
namespace {

// A manifold between two objects at the origin (its first body's frame is the world's), its
// breaking threshold 1 mm, holding a resting point at each of `points`.
struct Kept {
  btCollisionObject a, b;
  btPersistentManifold manifold{&a, &b, 0, 1e-3f, 1e-3f};
  explicit Kept(const std::vector<btVector3>& points) {
    for (const btVector3& p : points) {
      btManifoldPoint mp(p, p, btVector3(0, 0, 1), 0.0f);
      mp.m_appliedImpulse = 1.0f;
      manifold.addManifoldPoint(mp);
    }
  }
  bool holds(const btVector3& p) const {
    for (int k = 0; k < manifold.getNumContacts(); ++k)
      if ((manifold.getContactPoint(k).m_localPointA - p).length() < 1e-6f) return true;
    return false;
  }
};

const btVector3 kCorner[4] = {{-0.01f, -0.01f, 0}, {0.01f, -0.01f, 0}, {0.01f, 0.01f, 0}, {-0.01f, 0.01f, 0}};

TEST(ManifoldRoom, ANewPointEvictsTheKeptPointNearestItThatNoNewPointReplaces) {
  // Three corners and a stale point; this step: the three corners (one moved, less than the
  // threshold) and a new point nearer a refreshed corner (6 mm) than the stale point (14 mm).
  Kept kept({kCorner[0], kCorner[1], kCorner[2], btVector3(-0.01f, 0.004f, 0)});
  const std::array<btVector3, 4> chosen = {kCorner[0] + btVector3(2e-4f, 0, 0), kCorner[1], kCorner[2],
                                           btVector3(0.004f, 0.01f, 0)};
  makeRoomFor(kept.manifold, chosen);
  ASSERT_EQ(kept.manifold.getNumContacts(), 3);
  for (int c = 0; c < 3; ++c) EXPECT_TRUE(kept.holds(kCorner[c])) << c;
  EXPECT_FALSE(kept.holds(btVector3(-0.01f, 0.004f, 0)));
}

TEST(ManifoldRoom, KeptPointsNoNewPointNeedsStay) {
  // Room for one new point: the two kept points are not evicted while there is a free slot.
  Kept kept({kCorner[0], kCorner[1]});
  const std::array<btVector3, 2> chosen = {kCorner[0], kCorner[2]};
  makeRoomFor(kept.manifold, chosen);
  EXPECT_EQ(kept.manifold.getNumContacts(), 2);
  // Full, and four new points of which none meets a kept one: all four kept points go.
  Kept full({kCorner[0], kCorner[1], kCorner[2], kCorner[3]});
  const btVector3 shift(0.005f, 0, 0);
  const std::array<btVector3, 4> moved = {kCorner[0] + shift, kCorner[1] + shift, kCorner[2] + shift, kCorner[3] + shift};
  makeRoomFor(full.manifold, moved);
  EXPECT_EQ(full.manifold.getNumContacts(), 0);
}

TEST(ManifoldRoom, AnEmptyManifoldIsLeftAlone) {
  Kept kept({});
  const std::array<btVector3, 1> chosen = {kCorner[0]};
  makeRoomFor(kept.manifold, chosen);
  EXPECT_EQ(kept.manifold.getNumContacts(), 0);
}

}  // namespace
}  // namespace thx::phys::test::test_manifold_room
