#include "benchmarks/bench_physics_grounds.hpp"

#include <BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btInternalEdgeUtility.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>
#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <numbers>

#include "clients/physics/bullet_convert.hpp"
#include "textures/height_normals.hpp"

namespace thx::bench {

const char* repName(Rep r) {
  switch (r) {
    case Rep::Plain: return "plain plane";
    case Rep::Normal: return "normal map";
    case Rep::Relief: return "relief map";
    case Rep::Heightfield: return "heightfield";
    case Rep::Mesh: return "BVH mesh";
  }
  return "?";
}

long long residentBytes() {
  malloc_trim(0);
  std::ifstream statm("/proc/self/statm");
  long long size = 0, resident = 0;
  statm >> size >> resident;
  return resident * static_cast<long long>(sysconf(_SC_PAGESIZE));
}

namespace {

bool adjustEdgeContact(btManifoldPoint& cp, const btCollisionObjectWrapper* w0, int part0, int index0,
                       const btCollisionObjectWrapper* w1, int part1, int index1) {
  // The triangle (child of the mesh or heightfield) may be either object.
  if (w1->getCollisionShape()->getShapeType() == TRIANGLE_SHAPE_PROXYTYPE)
    btAdjustInternalEdgeContacts(cp, w1, w0, part1, index1);
  else if (w0->getCollisionShape()->getShapeType() == TRIANGLE_SHAPE_PROXYTYPE)
    btAdjustInternalEdgeContacts(cp, w0, w1, part0, index0);
  return true;
}

// btInternalEdgeUtility's thresholds assume metre-sized triangles: at 1 mm every triangle counts
// as degenerate and the map stays empty (docs/design.md §7 fact 8).
void tuneEdgeMap(btTriangleInfoMap& map, double spacing_m) {
  map.m_equalVertexThreshold = btScalar(1e-16);
  map.m_zeroAreaThreshold = btScalar(1e-16);
  map.m_edgeDistanceThreshold = static_cast<btScalar>(0.1 * spacing_m);
}

}  // namespace

void installEdgeCallback() { gContactAddedCallback = adjustEdgeContact; }

Ground::Ground(const SurfaceSpec& spec, Rep rep, int n, bool internal_edges) : spec_(spec), rep_(rep), n_(n) {
  const auto t0 = std::chrono::steady_clock::now();
  const double e = spec.extent_m, d = e / n;
  // Sample positions: texel centres. Texture rows run from +y (row 0) downwards; Bullet's
  // heightfield rows run from -y upwards. Both are sampled at their own points' coordinates, so
  // every representation holds the same N x N samples of h.
  auto coord = [&](int k) { return (k + 0.5) * d - 0.5 * e; };
  switch (rep) {
    case Rep::Plain:
      break;
    case Rep::Normal:
    case Rep::Relief: {
      tex::HeightField field(n, n);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) field.at(i, j) = spec.height(coord(i), -coord(j));
      tex::ReliefFromHeightOptions o;
      o.texel_m = {d, d};
      o.address = tex::Address::Clamp;  // slopes and bumps do not tile
      o.representation = rep == Rep::Relief ? tex::Representation::Relief : tex::Representation::Normal;
      map_ = std::make_unique<tex::TextureMap>(tex::reliefFromHeight(field, o));
      double h_max = field.heights_m.front();
      for (double h : field.heights_m) h_max = std::max(h_max, h);
      tex::PlaneMapping mapping;
      mapping.size_m = {e, e};
      // Relief: the plane frame's z = 0 is the highest sample (depth 0), so the relief surface
      // is at world z = h. Normal map: the flat plane is at z = 0 whatever h is (virtual relief).
      if (rep == Rep::Relief) mapping.plane_to_world.translation() = Eigen::Vector3d(0, 0, h_max);
      tex::SampleOptions sampling;
      sampling.address = tex::Address::Clamp;
      surface_ = tex::TexturedSurface(*map_, mapping, sampling, rep == Rep::Relief);
      source_bytes_ = static_cast<long long>(map_->bytes());
      break;
    }
    case Rep::Heightfield: {
      heights_.resize(std::size_t(n) * std::size_t(n));
      float lo = 1e30f, hi = -1e30f;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const float h = static_cast<float>(spec.height(coord(i), coord(j)));
          heights_[std::size_t(j) * std::size_t(n) + std::size_t(i)] = h;
          lo = std::min(lo, h);
          hi = std::max(hi, h);
        }
      // A flat field would give a zero-thickness AABB; give it 1 mm below.
      if (hi - lo < 1e-3f) lo = hi - 1e-3f;
      auto hf = std::make_unique<btHeightfieldTerrainShape>(n, n, heights_.data(), lo, hi, 2, false);
      hf->setLocalScaling(btVector3(static_cast<btScalar>(d), static_cast<btScalar>(d), 1));
      // The shape is centred on its AABB: heights are relative to the middle of [lo, hi].
      shape_pose_.translation() = Eigen::Vector3d(0, 0, 0.5 * (double(lo) + double(hi)));
      if (internal_edges) {
        edge_map_ = std::make_unique<btTriangleInfoMap>();
        tuneEdgeMap(*edge_map_, d);
        btGenerateInternalEdgeInfo(hf.get(), edge_map_.get());
      }
      shape_ = std::move(hf);
      source_bytes_ = static_cast<long long>(heights_.size() * sizeof(float));
      triangles_ = 2LL * (n - 1) * (n - 1);
      break;
    }
    case Rep::Mesh: {
      vertices_.reserve(3 * std::size_t(n) * std::size_t(n));
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const double x = coord(i), y = coord(j);
          vertices_.push_back(static_cast<float>(x));
          vertices_.push_back(static_cast<float>(y));
          vertices_.push_back(static_cast<float>(spec.height(x, y)));
        }
      indices_.reserve(6 * std::size_t(n - 1) * std::size_t(n - 1));
      for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
          const int a = j * n + i, b = a + 1, c = a + n + 1, dd = a + n;
          for (int v : {a, b, c, a, c, dd}) indices_.push_back(v);
        }
      triangles_ = static_cast<long long>(indices_.size() / 3);
      mesh_interface_ = std::make_unique<btTriangleIndexVertexArray>(
          static_cast<int>(triangles_), indices_.data(), int(3 * sizeof(int)), n * n, vertices_.data(),
          int(3 * sizeof(float)));
      auto mesh = std::make_unique<btBvhTriangleMeshShape>(mesh_interface_.get(), true, true);
      if (internal_edges) {
        edge_map_ = std::make_unique<btTriangleInfoMap>();
        tuneEdgeMap(*edge_map_, d);
        btGenerateInternalEdgeInfo(mesh.get(), edge_map_.get());
      }
      shape_ = std::move(mesh);
      source_bytes_ = static_cast<long long>(vertices_.size() * sizeof(float) + indices_.size() * sizeof(int));
      break;
    }
  }
  build_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

Ground::~Ground() = default;

btRigidBody& Ground::addTo(phys::PhysicsWorld& world, std::unique_ptr<btRigidBody>& keep) const {
  const phys::BodyMaterial material{1.0, 0.0, 0.0};
  switch (rep_) {
    case Rep::Plain: {
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      // z = -tan(t) x: the plane's normal leans towards +x.
      pose.linear() = Eigen::AngleAxisd(spec_.tilt_deg * std::numbers::pi / 180.0, Eigen::Vector3d::UnitY())
                          .toRotationMatrix();
      return world.addPlainPlane(pose, material);
    }
    case Rep::Normal:
      return world.addNormalMapPlane(surface_, material);
    case Rep::Relief:
      return world.addReliefPlane(surface_, material);
    case Rep::Heightfield:
    case Rep::Mesh: {
      btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, shape_.get(), btVector3(0, 0, 0));
      info.m_startWorldTransform = phys::toBt(shape_pose_);
      info.m_friction = static_cast<btScalar>(material.friction);
      keep = std::make_unique<btRigidBody>(info);
      if (edge_map_) keep->setCollisionFlags(keep->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
      world.world().addRigidBody(keep.get());
      return *keep;
    }
  }
  throw std::logic_error("unknown representation");
}

// Bodies never sleep here: the timed runs of a resting object measure its contacts' cost, and
// the rest checks its contacts' drift, not the rest criterion's freeze (docs/physics.md, "Rest").
static phys::WorldOptions awake() {
  phys::WorldOptions o;
  o.rest.enabled = false;
  return o;
}

Sim::Sim(const Ground& ground) : world(awake()) { ground.addTo(world, ground_body); }

Sim::~Sim() {
  if (ground_body) world.world().removeRigidBody(ground_body.get());
}

int Sim::contactPoints() {
  btDispatcher* d = world.world().getDispatcher();
  int count = 0;
  for (int m = 0; m < d->getNumManifolds(); ++m) count += d->getManifoldByIndexInternal(m)->getNumContacts();
  return count;
}

double Sim::manifoldBreakingThreshold() {
  btDispatcher* d = world.world().getDispatcher();
  for (int m = 0; m < d->getNumManifolds(); ++m) {
    const btPersistentManifold* mf = d->getManifoldByIndexInternal(m);
    if (mf->getBody0() == object || mf->getBody1() == object) return double(mf->getContactBreakingThreshold());
  }
  return 0.0;
}

}  // namespace thx::bench
