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
#include <array>
#include <cstdint>
#include <vector>

#include "server/halfspace_projection.hpp"
#include "server/triangle_mesh.hpp"

namespace thx::srv {

class TriangleBvh {
 public:
  static constexpr int kMaxDepth = 60;  // the traversal stack holds kMaxDepth + 2 nodes

  struct Hit {
    bool hit = false;
    double t = 0.0;                  // along a -> b, in [0, 1]
    std::uint32_t triangle = 0;      // index into mesh().triangles
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
  };

  // Leaves hold at most `leaf_size` triangles. The mesh must outlive the hierarchy. Throws
  // thx::Error (Config) on an empty mesh, a vertex index out of range or a degenerate
  // (zero-area) triangle.
  explicit TriangleBvh(const TriangleMesh& mesh, int leaf_size = 4);

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

  // The primitive test on one triangle (the same one firstEntry applies; tests compare the
  // hierarchy against it applied to every triangle).
  bool entersTriangle(std::uint32_t triangle, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double& t) const;

  // The triangle's plane: unit outward normal n and d = n . (any vertex).
  const Halfspace& plane(std::uint32_t triangle) const { return planes_[triangle]; }
  const TriangleMesh& mesh() const { return *mesh_; }
  std::size_t nodeCount() const { return nodes_.size(); }
  int depth() const { return depth_; }
  // Bytes of the hierarchy itself (nodes, leaf order, planes), beside mesh().bytes().
  std::size_t bytes() const;

 private:
  struct Node {
    std::array<double, 3> lo{}, hi{};
    std::uint32_t first_or_right = 0;  // leaf: first slot in order_; inner: right child (left = this + 1)
    std::uint32_t count = 0;           // leaf: triangles; 0 = inner node
  };
  std::uint32_t build(std::vector<Eigen::Vector3d>& centroids, std::uint32_t begin, std::uint32_t end, int depth);
  // A query segment a -> b with its reciprocal direction (per axis; `parallel` where b - a is 0).
  struct Segment {
    Eigen::Vector3d a = Eigen::Vector3d::Zero();
    Eigen::Vector3d inv_d = Eigen::Vector3d::Zero();
    std::array<bool, 3> parallel{};
  };
  static Segment segment(const Eigen::Vector3d& a, const Eigen::Vector3d& b);
  // Entry parameter of a + t (b - a) into the node's box within [0, t_max]; false if it misses.
  static bool boxEntry(const Node& node, const Segment& s, double t_max, double& t_enter);

  const TriangleMesh* mesh_;
  int leaf_size_;
  int depth_ = 0;
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> order_;  // triangle indices in leaf order
  std::vector<Halfspace> planes_;     // per triangle, mesh order
};

}  // namespace thx::srv
