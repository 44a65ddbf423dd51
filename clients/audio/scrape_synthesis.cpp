#include "clients/audio/scrape_synthesis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "clients/audio/meso_impulses.hpp"
#include "clients/audio/resonator_bank.hpp"

namespace thx::audio {
namespace {

struct Strike {
  std::size_t sample;
  int node;
  double impulse_ns;  // along the top face's normal (+z)
};

// The top-face node nearest to texture coordinates uv (wrapped into the one span of the slab).
int nearestTopNode(const TetMesh& slab, const std::vector<int>& top, tex::TexCoord uv, const Eigen::Vector2d& size) {
  const double u = uv.u - std::floor(uv.u), v = uv.v - std::floor(uv.v);
  const Eigen::Vector2d p((u - 0.5) * size.x(), (v - 0.5) * size.y());
  int best = top.front();
  double best_d = std::numeric_limits<double>::infinity();
  for (int n : top) {
    const double d = (slab.nodes[std::size_t(n)].head<2>() - p).squaredNorm();
    if (d < best_d) best_d = d, best = n;
  }
  return best;
}

}  // namespace

ScrapeRender renderScrape(const tex::TextureMap& map, const TetMesh& slab, const AudibleModes& modes,
                          std::span<const ScrapeSample> path, const ScrapeOptions& o) {
  ScrapeRender out;
  if (path.empty()) return out;
  std::vector<int> top;
  for (std::size_t n = 0; n < slab.nodes.size(); ++n)
    if (std::fabs(slab.nodes[n].z()) < 1e-12) top.push_back(int(n));

  // 1. The impulses, in time order.
  MesoSurface surface{&map, tex::Address::Wrap, {0, 0, 1}, o.pen_mass_kg, 0.05};
  std::vector<Strike> strikes;
  MesoState state;
  const std::int64_t first_tick = path.front().tick;
  for (std::size_t k = 1; k < path.size(); ++k) {
    const ScrapeSample &a = path[k - 1], &b = path[k];
    if (!a.in_contact || !b.in_contact || b.tick <= a.tick) {
      state = {};  // lifted: the next touch starts a new walk
      continue;
    }
    const double dt = double(b.tick - a.tick) / o.servo_hz;
    // Velocity in the texture's tangent frame: +x along u, +y along v.
    const Eigen::Vector3d v((b.uv.u - a.uv.u) * o.surface_size_m.x() / dt, (b.uv.v - a.uv.v) * o.surface_size_m.y() / dt, 0);
    const std::size_t at = std::size_t(std::llround(double(b.tick - first_tick) / o.servo_hz * o.sample_rate_hz));
    mesoImpulsesAlong(surface, state, a.uv, b.uv, v, [&](const MesoImpulse& m) {
      if (m.impulse.z() != 0.0) strikes.push_back({at, nearestTopNode(slab, top, b.uv, o.surface_size_m), m.impulse.z()});
      ++out.impulses;
    });
  }

  // 2. The bank, rendered block by block up to each strike.
  const double last_s = double(path.back().tick - first_tick) / o.servo_hz;
  const std::size_t total = std::size_t(std::ceil((last_s + o.tail_s) * o.sample_rate_hz)) + 1;
  std::vector<double> rendered(total, 0.0);
  if (modes.size() > 0) {
    ResonatorBank bank(o.sample_rate_hz, modes.size());
    bank.setModes(modes.frequency_hz, modes.decay_per_s);
    std::vector<double> g(modes.size());
    std::size_t done = 0;
    for (const Strike& s : strikes) {
      const std::size_t until = std::min(s.sample, total);
      if (until > done) bank.render(std::span<double>(rendered).subspan(done, until - done));
      done = std::max(done, until);
      for (std::size_t i = 0; i < modes.size(); ++i)
        g[i] = modes.shapes(Eigen::Index(3 * s.node + 2), Eigen::Index(i)) * s.impulse_ns;
      bank.strike(g);
    }
    if (total > done) bank.render(std::span<double>(rendered).subspan(done, total - done));
  }
  for (double x : rendered) out.raw_peak = std::max(out.raw_peak, std::fabs(x));
  const double gain = out.raw_peak > 0 ? o.peak / out.raw_peak : 0.0;
  out.samples.resize(total);
  for (std::size_t n = 0; n < total; ++n) out.samples[n] = float(rendered[n] * gain);
  return out;
}

}  // namespace thx::audio
