#include "clients/audio/synthesis/scrape_sites.hpp"

#include <cmath>
#include <limits>

#include "clients/audio/analysis/surface_nodes.hpp"

namespace thx::audio {

ScrapeSites ScrapeSites::slabTop(const TetMesh& slab, Eigen::Vector2d surface_size_m) {
  ScrapeSites s;
  s.mesh_ = &slab;
  s.size_ = surface_size_m;
  s.direction_.assign(slab.nodes.size(), Eigen::Vector3d::Zero());
  for (std::size_t n = 0; n < slab.nodes.size(); ++n)
    if (std::fabs(slab.nodes[n].z()) < 1e-12) {
      s.sites_.push_back(int(n));
      s.direction_[n] = Eigen::Vector3d::UnitZ();
    }
  s.initial_ = s.nearest({0.5, 0.5}, Eigen::Vector3d::Zero());
  return s;
}

ScrapeSites ScrapeSites::meshSurface(const TetMesh& solid, const Eigen::Isometry3d& mesh_to_world) {
  ScrapeSites s;
  s.mesh_ = &solid;
  s.on_mesh_ = true;
  s.world_to_mesh_ = mesh_to_world.inverse();
  s.direction_.assign(solid.nodes.size(), Eigen::Vector3d::Zero());
  const SurfaceNodes surface = surfaceNodes(solid);
  for (std::size_t n = 0; n < solid.nodes.size(); ++n) {
    const bool held = n < solid.clamped.size() && solid.clamped[n];
    if (!surface.on_surface[n] || held || surface.normal[n].squaredNorm() == 0.0) continue;
    s.sites_.push_back(int(n));
    s.direction_[n] = surface.normal[n].normalized();
  }
  s.initial_ = s.sites_.empty() ? 0 : s.sites_.front();
  return s;
}

int ScrapeSites::nearest(tex::TexCoord uv, const Eigen::Vector3d& p_world) const {
  int best = sites_.empty() ? 0 : sites_.front();
  double best_d = std::numeric_limits<double>::infinity();
  if (on_mesh_) {
    const Eigen::Vector3d p = world_to_mesh_ * p_world;
    for (int n : sites_) {
      const double d = (mesh_->nodes[std::size_t(n)] - p).squaredNorm();
      if (d < best_d) best_d = d, best = n;
    }
    return best;
  }
  const double u = uv.u - std::floor(uv.u), v = uv.v - std::floor(uv.v);
  const Eigen::Vector2d p((u - 0.5) * size_.x(), (v - 0.5) * size_.y());
  for (int n : sites_) {
    const double d = (mesh_->nodes[std::size_t(n)].head<2>() - p).squaredNorm();
    if (d < best_d) best_d = d, best = n;
  }
  return best;
}

}  // namespace thx::audio
