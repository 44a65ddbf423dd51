#pragma once
// Where the pen's scrape strikes the surface's body (pen_scrape.hpp), and along what:
//  - the plane's slab (slabMesh: top face at z = 0, centred on the origin, the texture's one span):
//    the top-face node nearest the tip's texture coordinates, struck along +z;
//  - a mesh scene's solid (scene_mesh_body.hpp, in the mesh's frame): the surface node nearest
//    the tip's point on the mesh (contact_t.p_proj_world moved into the mesh's frame), struck
//    along that node's outward normal (surface_nodes.hpp).
// The body receives -J along the direction for the pen's +J. The search is a scan over the
// candidate nodes (a few thousand for the bowl sounded at 48 segments), once per tick in contact.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "clients/audio/analysis/tet_mesh.hpp"
#include "textures/sampling.hpp"

namespace thx::audio {

class ScrapeSites {
 public:
  static ScrapeSites slabTop(const TetMesh& slab, Eigen::Vector2d surface_size_m);
  // Nodes held at zero are not struck (they cannot move).
  static ScrapeSites meshSurface(const TetMesh& solid, const Eigen::Isometry3d& mesh_to_world);

  // The node struck for a tip at texture coordinates uv (the slab) or world point p_world (a mesh).
  int nearest(tex::TexCoord uv, const Eigen::Vector3d& p_world) const;
  // Unit; the body receives -J along it. Zero for a node that is no site.
  const Eigen::Vector3d& direction(int node) const { return direction_[std::size_t(node)]; }
  // The node a render starts on, before any contact (the slab's centre; a mesh's first site).
  int initial() const { return initial_; }
  bool onMesh() const { return on_mesh_; }
  std::size_t size() const { return sites_.size(); }

 private:
  const TetMesh* mesh_ = nullptr;
  bool on_mesh_ = false;
  Eigen::Vector2d size_{0.2, 0.2};
  Eigen::Isometry3d world_to_mesh_ = Eigen::Isometry3d::Identity();
  std::vector<int> sites_;
  std::vector<Eigen::Vector3d> direction_;  // per node of the mesh
  int initial_ = 0;
};

}  // namespace thx::audio
