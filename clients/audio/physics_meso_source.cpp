#include "clients/audio/physics_meso_source.hpp"

#include <cmath>

#include "clients/audio/meso_impulses.hpp"

namespace thx::audio {

PhysicsMesoSource::PhysicsMesoSource(const tex::TextureMap& map, const TetMesh& slab, Eigen::Vector2d surface_size_m,
                                     std::uint32_t generation, std::int64_t playout_delay_ns)
    : map_(map), top_(slab, surface_size_m), generation_(generation), delay_ns_(playout_delay_ns) {}

void PhysicsMesoSource::physicsContacts(const thx_msgs::physics_contacts_t& m, std::int64_t receipt_ns,
                                        ExcitationSink& sink) {
  std::map<std::int32_t, Walk> still;  // the walks of the bodies in this message
  const Eigen::Vector3d ng(m.n_geometric_world[0], m.n_geometric_world[1], m.n_geometric_world[2]);
  const int n = std::min<int>(m.num_contacts, thx_msgs::physics_contacts_t::MAX_CONTACTS);
  for (int k = 0; k < n; ++k) {
    if (m.body_b[k] != thx_msgs::physics_contacts_t::BODY_SURFACE || m.body_a[k] == thx_msgs::physics_contacts_t::BODY_PEN)
      continue;
    const std::int32_t body = m.body_a[k];
    const MesoSurface surface{&map_, tex::Address::Wrap, ng, m.mass_a[k], 0.05};
    auto previous = walks_.find(body);
    bool started = previous != walks_.end();
    Walk walk = started ? previous->second : Walk{};
    const int first = m.path_start[k];
    for (int p = first; p < first + m.num_texels[k] && p < m.num_path && std::size_t(p) < m.path.size(); ++p) {
      if (p < 0) continue;
      const thx_msgs::physics_texel_t& t = m.path[std::size_t(p)];
      const Eigen::Vector3f ns(float(t.n_world[0]), float(t.n_world[1]), float(t.n_world[2]));
      if (started && (t.i != walk.i || t.j != walk.j)) {
        ++texels_;
        const Eigen::Vector3d v(t.v_world[0], t.v_world[1], t.v_world[2]);
        const double impulse = (mesoMomentum(surface, ns, v) - mesoMomentum(surface, walk.normal, v)).dot(ng);
        if (impulse != 0.0) {
          ExcitationEvent e;
          e.source_ns = m.utime * 1000;
          e.time_ns = e.source_ns + std::llround((t.t - m.sim_time + m.window) * 1e9) + delay_ns_;
          e.receipt_ns = receipt_ns;
          e.generation = generation_;
          e.body = 0;
          const tex::TexCoord uv{(t.i + 0.5) / map_.width(), 1.0 - (t.j + 0.5) / map_.height()};
          e.node = top_.nearest(uv);
          e.impulse[2] = impulse;
          sink.push(e);
        }
      }
      started = true;
      walk = Walk{t.i, t.j, ns};
    }
    if (started) still[body] = walk;
  }
  walks_ = std::move(still);
}

}  // namespace thx::audio
