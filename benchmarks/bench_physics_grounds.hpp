#pragma once
// bench_physics: the same surface in five representations (plain plane, normal map, relief map,
// btHeightfieldTerrainShape, btBvhTriangleMeshShape), each built from one analytic height field
// sampled at the same N x N points (the texel centres), and small single-body worlds on them.
// Not real-time code.
#include <BulletCollision/CollisionShapes/btCollisionShape.h>
#include <BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h>
#include <BulletCollision/CollisionShapes/btTriangleInfoMap.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "clients/physics/physics_world.hpp"
#include "textures/texture_map.hpp"
#include "textures/textured_surface.hpp"

namespace thx::bench {

enum class Rep { Plain, Normal, Relief, Heightfield, Mesh };
const char* repName(Rep r);

// A surface z = h(x, y) over the square [-extent/2, extent/2]^2 (world frame, z up, metres).
// `tilt_deg` != 0 marks a uniform slope z = -tan(tilt) x, which the plain plane can represent
// exactly (a tilted btStaticPlaneShape); other surfaces have no plain-plane form except flat.
struct SurfaceSpec {
  std::string name;
  double extent_m = 0.5;
  std::function<double(double, double)> height;
  double tilt_deg = 0.0;
  bool flat = false;
};

// One representation of a surface at N samples per side, owning everything it needs.
// Heightfield and mesh shapes are shared by every world made on this ground.
class Ground {
 public:
  // internal_edges (heightfield and mesh only): Bullet's btInternalEdgeUtility, with its
  // thresholds scaled to millimetre triangles (docs/design.md §7 fact 8): the info map is built
  // here and the static body gets CF_CUSTOM_MATERIAL_CALLBACK; installEdgeCallback() must have run.
  Ground(const SurfaceSpec& spec, Rep rep, int n, bool internal_edges = false);
  ~Ground();
  Ground(const Ground&) = delete;
  Ground& operator=(const Ground&) = delete;

  Rep rep() const { return rep_; }
  int samples() const { return n_; }
  double buildMs() const { return build_ms_; }
  long long sourceBytes() const { return source_bytes_; }  // our arrays / texture (what we allocated)
  long long triangles() const { return triangles_; }
  const btCollisionShape* sharedShape() const { return shape_.get(); }
  bool internalEdges() const { return edge_map_ != nullptr; }
  long long edgeMapEntries() const { return edge_map_ ? static_cast<long long>(edge_map_->size()) : 0; }

  // Adds this ground to `world` as a static body with friction 1 (Bullet multiplies the
  // frictions, so the object's decides). Returns the body (owned by `keep` or by the world).
  btRigidBody& addTo(phys::PhysicsWorld& world, std::unique_ptr<btRigidBody>& keep) const;

 private:
  SurfaceSpec spec_;
  Rep rep_;
  int n_;
  double build_ms_ = 0.0;
  long long source_bytes_ = 0;
  long long triangles_ = 0;
  // Normal / relief.
  std::unique_ptr<tex::TextureMap> map_;
  tex::TexturedSurface surface_;
  // Heightfield / mesh.
  std::vector<float> heights_;
  std::vector<float> vertices_;
  std::vector<int> indices_;
  std::unique_ptr<btTriangleIndexVertexArray> mesh_interface_;
  std::unique_ptr<btCollisionShape> shape_;
  std::unique_ptr<btTriangleInfoMap> edge_map_;
  Eigen::Isometry3d shape_pose_ = Eigen::Isometry3d::Identity();
};

// A single-body world on a ground; removes the shared-shape body before the world goes.
struct Sim {
  phys::PhysicsWorld world;
  std::unique_ptr<btRigidBody> ground_body;  // only for shared shapes
  btRigidBody* object = nullptr;
  explicit Sim(const Ground& ground);
  ~Sim();
  Sim(const Sim&) = delete;
  Sim& operator=(const Sim&) = delete;
  // Contact points in all manifolds after the last step.
  int contactPoints();
  // The breaking threshold of the object's manifold (0 if none yet).
  double manifoldBreakingThreshold();
};

// Installs the global gContactAddedCallback that lets btAdjustInternalEdgeContacts fix contact
// normals on grounds built with internal_edges (it fires only for bodies flagged
// CF_CUSTOM_MATERIAL_CALLBACK, so other grounds are not affected).
void installEdgeCallback();

// Resident set size of this process (bytes), after returning freed heap memory to the OS.
long long residentBytes();

}  // namespace thx::bench
