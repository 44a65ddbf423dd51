#pragma once
// An axis-aligned bounding-volume hierarchy over a triangle mesh, for the mesh god object's
// swept-segment queries (mesh_god_object.hpp). Built once (allocates); queries are real-time
// safe: no allocation, a fixed traversal stack (the build bounds the depth), no locks.
//
// The query is the god object's only collision question: the FIRST triangle a segment a -> b
// ENTERS through its front (n . a - d >= 0 > n . b - d, n the triangle's outward normal), so a
// proxy outside the surface learns which face its motion toward the tip runs into. Back faces are
// not hits: a proxy never starts inside. Barycentric coordinates are accepted within a relative
// 1e-9, so a segment through a shared edge or vertex finds a triangle on at least one side (no
// crack between neighbours); ties in t go to the lower triangle index, so the answer is unique.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "server/halfspace_projection.hpp"
#include "server/triangle_mesh.hpp"

namespace thx::srv {

// A query segment a -> b with its reciprocal direction (per axis; `parallel` where b - a is 0),
// and the slab test every box of a sweep goes through (the hierarchy's nodes, the local set's
// leaves: local_triangle_set.hpp).
struct SweepSegment {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  Eigen::Vector3d inv_d = Eigen::Vector3d::Zero();
  std::array<bool, 3> parallel{};
};
SweepSegment sweepSegment(const Eigen::Vector3d& a, const Eigen::Vector3d& b);
// A triangle as a sweep's entry test reads it: its plane, a corner p0, the edges from it
// e1 = p1 - p0 and e2 = p2 - p0, their cross product n and 1 / |n|^2. The hierarchy works them out
// from the mesh at each test; the local set (local_triangle_set.hpp) keeps them for the triangles
// around the pen, where the sweeps read them from a few kilobytes gathered ahead of the pen.
struct EntryCorners {
  Eigen::Vector3d p0 = Eigen::Vector3d::Zero(), e1 = Eigen::Vector3d::Zero(), e2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  double inv_area2 = 0.0;
};
struct EntryTriangle {
  Halfspace plane;
  EntryCorners corners;
  std::uint32_t index = 0;  // in the mesh
};
// The entry test in two halves, shared by every sweep so that all answer alike to the bit:
// where a -> b crosses the plane from its front (s, within t_max) ...
inline bool crossesFront(const Halfspace& h, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double t_max,
                         double& s) {
  const double sa = h.n.dot(a) - h.d, sb = h.n.dot(b) - h.d;
  if (!(sa >= 0.0 && sb < 0.0)) return false;  // not entering through the front
  s = sa / (sa - sb);
  return !(s > t_max);
}
// ... and whether that point lies in the triangle, barycentric coordinates within a relative
// kBarycentricTol (a hit on a shared edge belongs to both sides).
inline constexpr double kBarycentricTol = 1e-9;
inline bool insideAt(const EntryCorners& c, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double s) {
  const Eigen::Vector3d w = a + s * (b - a) - c.p0;
  const double l1 = w.cross(c.e2).dot(c.n) * c.inv_area2;  // weight of vertex 1
  const double l2 = c.e1.cross(w).dot(c.n) * c.inv_area2;  // weight of vertex 2
  return !(l1 < -kBarycentricTol || l2 < -kBarycentricTol || l1 + l2 > 1.0 + kBarycentricTol);
}
inline bool entersTriangle(const EntryTriangle& tri, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double t_max,
                           double& t) {
  double s = 0.0;
  if (!crossesFront(tri.plane, a, b, t_max, s) || !insideAt(tri.corners, a, b, s)) return false;
  t = s;
  return true;
}

// Entry parameter of a + t (b - a) into the box [lo, hi] within [0, t_max]; false if it misses.
inline bool slabEntry(const std::array<double, 3>& lo_box, const std::array<double, 3>& hi_box, const SweepSegment& s,
                      double t_max, double& t_enter) {
  // Slabs with the reciprocal direction computed once per query (three divisions per box were a
  // third of a tick's BVH time, bench_mesh_force). Multiplying by the reciprocal rounds slightly
  // differently from dividing, so the slab interval is widened by kSlabSlack: a box is never
  // missed, and its entry never overestimated, by that rounding; the triangles decide exactly.
  constexpr double kSlabSlack = 1e-12;
  double t0 = 0.0, t1 = t_max;
  for (int k = 0; k < 3; ++k) {
    const double lo = lo_box[std::size_t(k)], hi = hi_box[std::size_t(k)];
    if (s.parallel[std::size_t(k)]) {
      if (s.a[k] < lo || s.a[k] > hi) return false;
      continue;
    }
    double ta = (lo - s.a[k]) * s.inv_d[k], tb = (hi - s.a[k]) * s.inv_d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta - kSlabSlack);
    t1 = std::min(t1, tb + kSlabSlack);
    if (t0 > t1) return false;
  }
  t_enter = t0;
  return true;
}

class TriangleBvh {
 public:
  static constexpr int kMaxDepth = 60;  // the traversal stack holds kMaxDepth + 2 nodes

  struct Hit {
    bool hit = false;
    double t = 0.0;                  // along a -> b, in [0, 1]
    std::uint32_t triangle = 0;      // index into triangles()
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
  };

  // Leaves hold at most `leaf_size` triangles. The mesh must outlive the hierarchy. Throws
  // thx::Error (Config) on an empty mesh, a vertex index out of range or a degenerate
  // (zero-area) triangle.
  explicit TriangleBvh(const TriangleMesh& mesh, int leaf_size = 4);
  // Over the two arrays of a mesh held elsewhere (a textured mesh's positions and triangles), so
  // that the sweeps and the renderer read one copy of the corners (docs/meshes.md). Both must
  // outlive the hierarchy.
  TriangleBvh(const std::vector<Eigen::Vector3d>& vertices, const std::vector<std::array<std::uint32_t, 3>>& triangles,
              int leaf_size = 4);
  // The hierarchy keeps pointers to its mesh's arrays: a temporary's would dangle.
  TriangleBvh(TriangleMesh&&, int = 4) = delete;
  TriangleBvh(std::vector<Eigen::Vector3d>&&, const std::vector<std::array<std::uint32_t, 3>>&, int = 4) = delete;
  TriangleBvh(const std::vector<Eigen::Vector3d>&, std::vector<std::array<std::uint32_t, 3>>&&, int = 4) = delete;

  // What a sweep keeps while it looks: the least entry parameter so far and its triangle.
  struct Best {
    double t = std::numeric_limits<double>::infinity();
    std::uint32_t triangle = 0;
  };
  // The rules every sweep keeps its answer by, so that all answer alike: a triangle in `skip` is
  // passed over; an entry at t is kept if it is the least so far, ties to the lower triangle.
  static bool skipped(const std::uint32_t* skip, int n_skip, std::uint32_t triangle) {
    bool found = false;
    for (int s = 0; s < n_skip; ++s) found = found || skip[s] == triangle;
    return found;
  }
  static bool keepIfFirst(Best& best, double t, std::uint32_t triangle) {
    if (!(t < best.t || (t == best.t && triangle < best.triangle))) return false;
    best.t = t;
    best.triangle = triangle;
    return true;
  }
  // The triangles of one leaf (slots first .. first + count - 1) tested against a -> b, skipping
  // the `n_skip` triangles in `skip`: `best` keeps the least entry, ties to the lower triangle;
  // true if this leaf changed it. The hierarchy's sweep and the local set's (local_triangle_set.hpp)
  // both test their leaves so, which is why their answers are the same.
  bool enterLeaf(std::uint32_t first, std::uint32_t count, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                 const std::uint32_t* skip, int n_skip, Best& best) const;
  // The hit of a sweep a -> b that kept `best` (none if nothing was entered within [0, 1]).
  static Hit hitOf(const Best& best, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

  // The first front-face entry of a -> b, skipping the `n_skip` triangles in `skip`.
  Hit firstEntry(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const std::uint32_t* skip = nullptr,
                 int n_skip = 0) const;
  struct Nearest {
    bool found = false;
    std::uint32_t triangle = 0;
    Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
    double distance = 0.0;
  };
  // The triangle closest to p within max_distance (ties to the lower index). The textured mesh
  // renderer asks it where the proxy stands beyond the edge of the face that holds it.
  Nearest nearest(const Eigen::Vector3d& p, double max_distance) const;

  // An incremental box query, so that its work can be spread over servo ticks
  // (local_triangle_set.hpp): startWalk(box), then stepWalk(budget, on_leaf) visits at most
  // `budget` nodes per call and calls on_leaf(first slot, count, lo, hi) for every leaf whose box
  // meets the query box (closed boxes); it returns true once every node is visited. A leaf is
  // swept with enterLeaf(first, count, ...).
  struct BoxWalk {
    std::array<double, 3> lo{}, hi{};
    std::array<std::uint32_t, kMaxDepth + 2> stack{};
    int sp = 0;
  };
  void startWalk(BoxWalk& walk, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
    for (int k = 0; k < 3; ++k) walk.lo[std::size_t(k)] = lo[k], walk.hi[std::size_t(k)] = hi[k];
    walk.stack[0] = 0;
    walk.sp = 1;
  }
  template <class OnLeaf>
  bool stepWalk(BoxWalk& walk, int budget, OnLeaf&& on_leaf) const {
    for (; budget > 0 && walk.sp > 0; --budget) {
      const std::uint32_t index = walk.stack[std::size_t(--walk.sp)];
      const Node& node = nodes_[index];
      bool meets = true;
      for (std::size_t k = 0; k < 3; ++k) meets = meets && node.lo[k] <= walk.hi[k] && node.hi[k] >= walk.lo[k];
      if (!meets) continue;
      if (node.count > 0) {
        on_leaf(node.first_or_right, node.count, node.lo, node.hi);
        continue;
      }
      // Both children's boxes are asked for now and read later (a walk ahead of the pen meets
      // nodes no tick has touched yet).
      __builtin_prefetch(&nodes_[node.first_or_right]);
      __builtin_prefetch(&nodes_[index + 1]);
      walk.stack[std::size_t(walk.sp++)] = node.first_or_right;
      walk.stack[std::size_t(walk.sp++)] = index + 1;
    }
    return walk.sp == 0;
  }
  // The median over the leaves of their boxes' largest side (the local set's scale).
  double typicalLeafExtent() const;

  // The primitive test on one triangle (the same one firstEntry applies; tests compare the
  // hierarchy against it applied to every triangle).
  bool entersTriangle(std::uint32_t triangle, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double& t) const {
    return entersTriangleBy(triangle, a, b, std::numeric_limits<double>::infinity(), t);
  }
  // The same test, false early for an entry beyond t_max (the same t where it is not).
  bool entersTriangleBy(std::uint32_t triangle, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double t_max,
                        double& t) const;

  // The triangle as the entry test reads it (EntryTriangle), and its corners' part alone.
  EntryCorners entryCorners(std::uint32_t triangle) const {
    EntryCorners c;
    const auto& tri = (*triangles_)[triangle];
    c.p0 = (*vertices_)[tri[0]];
    c.e1 = (*vertices_)[tri[1]] - c.p0;
    c.e2 = (*vertices_)[tri[2]] - c.p0;
    c.n = c.e1.cross(c.e2);
    c.inv_area2 = 1.0 / c.n.squaredNorm();
    return c;
  }
  EntryTriangle entryTriangle(std::uint32_t triangle) const { return {planes_[triangle], entryCorners(triangle), triangle}; }
  // The triangle in a leaf's slot (enterLeaf's first .. first + count - 1).
  std::uint32_t leafTriangle(std::uint32_t slot) const { return order_[slot]; }
  // The triangle's plane: unit outward normal n and d = n . (any vertex).
  const Halfspace& plane(std::uint32_t triangle) const { return planes_[triangle]; }
  const std::vector<Eigen::Vector3d>& vertices() const { return *vertices_; }
  const std::vector<std::array<std::uint32_t, 3>>& triangles() const { return *triangles_; }
  std::size_t nodeCount() const { return nodes_.size(); }
  int depth() const { return depth_; }
  // Bytes of the hierarchy itself (nodes, leaf order, planes), beside its mesh's.
  std::size_t bytes() const;

 private:
  struct Node {
    std::array<double, 3> lo{}, hi{};
    std::uint32_t first_or_right = 0;  // leaf: first slot in order_; inner: right child (left = this + 1)
    std::uint32_t count = 0;           // leaf: triangles; 0 = inner node
  };
  std::uint32_t build(std::vector<Eigen::Vector3d>& centroids, std::uint32_t begin, std::uint32_t end, int depth);

  const std::vector<Eigen::Vector3d>* vertices_;
  const std::vector<std::array<std::uint32_t, 3>>* triangles_;
  int leaf_size_;
  int depth_ = 0;
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> order_;  // triangle indices in leaf order
  std::vector<Halfspace> planes_;     // per triangle, mesh order
};

}  // namespace thx::srv
