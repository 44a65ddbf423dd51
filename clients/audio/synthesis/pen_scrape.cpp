#include "clients/audio/synthesis/pen_scrape.hpp"

#include <cmath>

namespace thx::audio {

ScrapeSample scrapeSample(const thx_msgs::contact_t& c) {
  const auto v3 = [](const double* x) { return Eigen::Vector3d(x[0], x[1], x[2]); };
  return {c.tick, c.in_contact != 0, {c.uv[0], c.uv[1]}, c.f_normal, v3(c.n_geom_world), v3(c.n_sampled_world),
          v3(c.v_tangent_world), v3(c.p_proj_world)};
}

PenScrape::PenScrape(const tex::TextureMap& map, const TetMesh& slab, PenScrapeOptions options)
    : options_(options),
      surface_{&map, tex::Address::Wrap, {0, 0, 1}, options.pen_mass_kg, options.min_normal_dot},
      sites_(options.mesh_to_world ? ScrapeSites::meshSurface(slab, *options.mesh_to_world)
                                   : ScrapeSites::slabTop(slab, options.surface_size_m)) {}

bool PenScrape::withinReach(tex::TexCoord from, tex::TexCoord to, double moved_m) const {
  const tex::TextureMap& map = *surface_.map;
  const double du = std::fabs(to.u - from.u) * map.width(), dv = std::fabs(to.v - from.v) * map.height();
  const double can_u = 2.0 * moved_m / (options_.surface_size_m.x() / map.width()) + 2.0;
  const double can_v = 2.0 * moved_m / (options_.surface_size_m.y() / map.height()) + 2.0;
  return du <= can_u && dv <= can_v;
}

void PenScrape::reset() {
  state_ = {};
  have_previous_ = false;
}

}  // namespace thx::audio
