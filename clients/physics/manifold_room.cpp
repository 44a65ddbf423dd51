#include "clients/physics/manifold_room.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>

#include <algorithm>
#include <array>
#include <functional>
#include <limits>

namespace thx::phys {

namespace {

constexpr int kSlots = MANIFOLD_CACHE_SIZE;

// Which kept points the new ones will replace, as Bullet's cache will see them while the new ones
// are added in turn (btPersistentManifold::getCacheEntry: the nearest on the first body within
// the breaking threshold, which then stands where the new one is), and the new points that meet
// none (the first body's frame).
struct Matches {
  int kept = 0;
  std::array<btVector3, kSlots> local{};  // the kept points, as replaced
  std::array<bool, kSlots> claimed{};
  std::array<btVector3, kSlots> unmet{};
  int unmet_count = 0;
};

Matches match(const btPersistentManifold& manifold, std::span<const btVector3> on_object) {
  Matches m;
  m.kept = manifold.getNumContacts();
  const btTransform& body = manifold.getBody0()->getWorldTransform();
  const btScalar reach2 = manifold.getContactBreakingThreshold() * manifold.getContactBreakingThreshold();
  for (int k = 0; k < m.kept; ++k) m.local[std::size_t(k)] = manifold.getContactPoint(k).m_localPointA;
  for (const btVector3& world : on_object) {
    const btVector3 a = body.invXform(world);
    int nearest = -1;
    btScalar best = reach2;
    for (int k = 0; k < m.kept; ++k) {
      const btScalar d2 = (m.local[std::size_t(k)] - a).length2();
      if (d2 < best) best = d2, nearest = k;
    }
    if (nearest >= 0) {
      m.local[std::size_t(nearest)] = a;
      m.claimed[std::size_t(nearest)] = true;
    } else if (m.unmet_count < kSlots) {
      m.unmet[std::size_t(m.unmet_count++)] = a;
    }
  }
  return m;
}

// Highest index first: removeContactPoint moves the last point into the freed index.
void removeAll(btPersistentManifold& manifold, std::array<int, kSlots>& indices, int count) {
  std::sort(indices.begin(), indices.begin() + count, std::greater<int>());
  for (int e = 0; e < count; ++e) manifold.removeContactPoint(indices[std::size_t(e)]);
}

}  // namespace

void makeRoomFor(btPersistentManifold& manifold, std::span<const btVector3> on_object) {
  if (manifold.getNumContacts() == 0) return;
  Matches m = match(manifold, on_object);
  int evict = m.unmet_count - (kSlots - m.kept);
  std::array<int, kSlots> evicted{};
  int evicted_count = 0;
  for (int u = 0; u < m.unmet_count && evict > 0; ++u, --evict) {
    int nearest = -1;
    btScalar best = std::numeric_limits<btScalar>::max();
    for (int k = 0; k < m.kept; ++k) {
      if (m.claimed[std::size_t(k)]) continue;
      const btScalar d2 = (m.local[std::size_t(k)] - m.unmet[std::size_t(u)]).length2();
      if (d2 < best) best = d2, nearest = k;
    }
    if (nearest < 0) break;  // every kept point is replaced: not with at most four new points
    m.claimed[std::size_t(nearest)] = true;
    evicted[std::size_t(evicted_count++)] = nearest;
  }
  removeAll(manifold, evicted, evicted_count);
}

}  // namespace thx::phys
