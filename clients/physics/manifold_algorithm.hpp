#pragma once
// What our own collision algorithms (relief_collision.hpp, scaled_convex_collision.hpp) share:
// one persistent manifold for the pair, made on first use unless Bullet hands one in, released
// with the algorithm; discrete contacts only (no time of impact).
#include <BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btCollisionCreateFunc.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>

#include <new>

namespace thx::phys {

class ManifoldAlgorithm : public btActivatingCollisionAlgorithm {
 public:
  ManifoldAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* body0,
                    const btCollisionObjectWrapper* body1)
      : btActivatingCollisionAlgorithm(ci, body0, body1), manifold_(ci.m_manifold) {}
  ~ManifoldAlgorithm() override {
    if (own_manifold_ && manifold_) m_dispatcher->releaseManifold(manifold_);
  }

  btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                 btManifoldResult*) override {
    return btScalar(1);  // discrete contacts only, like the rest of the world
  }
  void getAllContactManifolds(btManifoldArray& manifolds) override {
    if (manifold_ && own_manifold_) manifolds.push_back(manifold_);
  }

  // Bullet's create function for an algorithm type whose constructor takes (ci, body0, body1,
  // args...). Algorithms come from the dispatcher's pool, sized for Bullet's own: keep them small.
  template <class Algorithm, class... Args>
  static btCollisionAlgorithm* create(btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* body0,
                                      const btCollisionObjectWrapper* body1, Args... args) {
    void* memory = ci.m_dispatcher1->allocateCollisionAlgorithm(int(sizeof(Algorithm)));
    return new (memory) Algorithm(ci, body0, body1, args...);
  }

 protected:
  // The pair's manifold, made between these two objects (in this order) on first use.
  btPersistentManifold* manifoldFor(const btCollisionObject* first, const btCollisionObject* second) {
    if (!manifold_) {
      manifold_ = m_dispatcher->getNewManifold(first, second);
      own_manifold_ = true;
    }
    return manifold_;
  }
  bool ownsManifold() const { return own_manifold_; }

 private:
  btPersistentManifold* manifold_ = nullptr;
  bool own_manifold_ = false;
};

}  // namespace thx::phys
