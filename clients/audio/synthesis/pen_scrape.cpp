#include "clients/audio/synthesis/pen_scrape.hpp"

#include <cmath>
#include <limits>

namespace thx::audio {

ScrapeSample scrapeSample(const thx_msgs::contact_t& c) {
  const auto v3 = [](const double* x) { return Eigen::Vector3d(x[0], x[1], x[2]); };
  return {c.tick, c.in_contact != 0, {c.uv[0], c.uv[1]}, c.f_normal, v3(c.n_geom_world), v3(c.n_sampled_world),
          v3(c.v_tangent_world)};
}

SlabTopFace::SlabTopFace(const TetMesh& slab, Eigen::Vector2d surface_size_m) : slab_(slab), size_(surface_size_m) {
  for (std::size_t n = 0; n < slab.nodes.size(); ++n)
    if (std::fabs(slab.nodes[n].z()) < 1e-12) top_.push_back(int(n));
}

int SlabTopFace::nearest(tex::TexCoord uv) const {
  const double u = uv.u - std::floor(uv.u), v = uv.v - std::floor(uv.v);
  const Eigen::Vector2d p((u - 0.5) * size_.x(), (v - 0.5) * size_.y());
  int best = top_.empty() ? 0 : top_.front();
  double best_d = std::numeric_limits<double>::infinity();
  for (int n : top_) {
    const double d = (slab_.nodes[std::size_t(n)].head<2>() - p).squaredNorm();
    if (d < best_d) best_d = d, best = n;
  }
  return best;
}

PenScrape::PenScrape(const tex::TextureMap& map, const TetMesh& slab, PenScrapeOptions options)
    : options_(options),
      surface_{&map, tex::Address::Wrap, {0, 0, 1}, options.pen_mass_kg, options.min_normal_dot},
      top_(slab, options.surface_size_m) {}

void PenScrape::reset() {
  state_ = {};
  have_previous_ = false;
}

}  // namespace thx::audio
