#pragma once
// The first triangle of a TexturedMesh a ray meets, front faces only (back faces are culled, as
// the rasteriser culls them), through a bounding volume hierarchy: the CPU reference's
// visibility, fast enough for a 100,000-triangle mesh at 1280x720 (the benchmark's error).
// Built once (allocates); firstHit() allocates nothing.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

#include "meshes/textured_mesh.hpp"

namespace thx::visual {

struct MeshRayHit {
  std::uint32_t triangle = 0;
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();  // of the triangle's corners 0, 1, 2
  double t = 0.0;                                         // origin + t * direction
};

class MeshRayCaster {
 public:
  explicit MeshRayCaster(const mesh::TexturedMesh& mesh);  // the mesh must outlive the caster
  // Mesh frame. A front face is one whose counter-clockwise side faces the origin; t > 0.
  std::optional<MeshRayHit> firstHit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) const;

 private:
  // A leaf holds count > 0 triangles from order_[first]; an inner node's children are nodes
  // first and first + 1.
  struct Node {
    Eigen::AlignedBox3d box;
    std::uint32_t first = 0, count = 0;
  };
  static constexpr std::uint32_t kLeafSize = 4;
  static constexpr int kMaxDepth = 64;  // median splits: depth ~ log2(triangles / kLeafSize)
  void build(std::uint32_t node, std::uint32_t begin, std::uint32_t end, int depth);

  const mesh::TexturedMesh* mesh_;
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> order_;
  std::vector<Eigen::Vector3d> centroids_;
};

}  // namespace thx::visual
