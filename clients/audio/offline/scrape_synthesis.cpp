#include "clients/audio/offline/scrape_synthesis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "clients/audio/synthesis/resonator_bank.hpp"

namespace thx::audio {
namespace {

// One body's modes driven by a modal impulse per sample: gain[i] x impulse[n] on mode i. Runs of
// silent input are rendered as one block (the bank's output does not depend on the blocking).
void renderBody(const AudibleModes& modes, const std::vector<double>& gain_per_mode_sample_node,
                const std::vector<int>& node_of_sample, const std::vector<double>& impulse, double sample_rate_hz,
                std::size_t modes_per_node, std::vector<double>& out) {
  if (modes.size() == 0) return;
  ResonatorBank bank(sample_rate_hz, modes.size());
  bank.setModes(modes.frequency_hz, modes.decay_per_s);
  std::vector<double> g(modes.size());
  std::vector<double> block(out.size(), 0.0);
  std::size_t n = 0;
  while (n < out.size()) {
    if (impulse[n] == 0.0) {
      std::size_t end = n;
      while (end < out.size() && impulse[end] == 0.0) ++end;
      bank.render(std::span<double>(block).subspan(n, end - n));
      n = end;
      continue;
    }
    const std::size_t row = std::size_t(node_of_sample[n]) * modes_per_node;
    for (std::size_t i = 0; i < modes.size(); ++i) g[i] = gain_per_mode_sample_node[row + i] * impulse[n];
    bank.strike(g);
    bank.render(std::span<double>(block).subspan(n, 1));
    ++n;
  }
  for (std::size_t k = 0; k < out.size(); ++k) out[k] += block[k];
}

}  // namespace

PenScrapeOptions penScrapeOptions(const ScrapeOptions& o) {
  PenScrapeOptions p;
  p.servo_hz = o.servo_hz;
  p.pen_mass_kg = o.pen_mass_kg;
  p.surface_size_m = o.surface_size_m;
  p.meso = o.meso;
  p.mesh_to_world = o.mesh_to_world;
  return p;
}

ScrapeExcitation scrapeExcitation(const tex::TextureMap& map, const TetMesh& slab, std::span<const ScrapeSample> path,
                                  const ScrapeOptions& o) {
  ScrapeExcitation e;
  if (path.empty()) return e;
  const std::int64_t first_tick = o.origin_tick ? *o.origin_tick : path.front().tick;
  auto sampleOf = [&](std::int64_t tick) {
    return std::size_t(std::llround(double(tick - first_tick) / o.servo_hz * o.sample_rate_hz));
  };
  const double last_s = double(path.back().tick - first_tick) / o.servo_hz;
  const std::size_t total = std::size_t(std::ceil((last_s + o.tail_s) * o.sample_rate_hz)) + 1;
  e.impulse_ns.assign(total, 0.0);
  if (slab.nodes.empty()) {
    e.slab_node.assign(total, 0);
    return e;
  }
  PenScrape scrape(map, slab, penScrapeOptions(o));
  e.slab_node.assign(total, scrape.sites().initial());

  const bool micro = o.roughness.amplitude > 0.0;
  const RoughnessProfile profile(micro ? o.roughness : RoughnessOptions{});
  std::vector<double> force;
  double micro_power = 0.0;
  std::size_t micro_samples = 0;
  for (const ScrapeSample& s : path) {
    e.impulses += scrape.next(
        s,
        [&](const PenStrike& p) {
          e.impulse_ns[std::min(sampleOf(p.tick), total - 1)] += p.impulse_ns;
          ++e.nonzero_impulses;
        },
        [&](const PenMicroSegment& m) {
          const std::size_t at_a = std::min(sampleOf(m.tick_a), total - 1), at_b = std::min(sampleOf(m.tick_b), total - 1);
          for (std::size_t n = at_a + 1; n <= at_b; ++n) e.slab_node[n] = m.node;
          if (!micro || at_b <= at_a) return;
          force.assign(at_b - at_a, 0.0);
          microForce(profile, m.s0, m.s1, m.f0, m.f1, force);
          for (std::size_t n = 0; n < force.size(); ++n) {
            e.impulse_ns[at_a + 1 + n] += force[n] / o.sample_rate_hz;
            micro_power += force[n] * force[n];
          }
          micro_samples += force.size();
        });
  }
  e.micro_rms_n = micro_samples ? std::sqrt(micro_power / double(micro_samples)) : 0.0;
  e.micro_samples = micro_samples;
  return e;
}

ScrapeRender scrapeDisplacement(const tex::TextureMap& map, const TetMesh& slab, const AudibleModes& modes,
                                std::span<const ScrapeSample> path, const ScrapeOptions& o, const PenModes* pen) {
  ScrapeRender out;
  if (path.empty()) return out;
  const ScrapeExcitation e = scrapeExcitation(map, slab, path, o);
  out.impulses = e.impulses;
  out.nonzero_impulses = e.nonzero_impulses;
  out.micro_rms_n = e.micro_rms_n;
  out.micro_samples = e.micro_samples;
  const std::size_t total = e.impulse_ns.size();

  // The body receives -J along the node's direction (the slab's top face: +z): the gain of each
  // mode at each node.
  std::vector<double> slab_gain(slab.nodes.size() * modes.size());
  if (o.mesh_to_world) {
    const ScrapeSites sites = ScrapeSites::meshSurface(slab, *o.mesh_to_world);
    for (std::size_t n = 0; n < slab.nodes.size(); ++n)
      for (std::size_t i = 0; i < modes.size(); ++i)
        slab_gain[n * modes.size() + i] =
            -modes.shapes.block(Eigen::Index(3 * n), Eigen::Index(i), 3, 1).col(0).dot(sites.direction(int(n)));
  } else {
    for (std::size_t n = 0; n < slab.nodes.size(); ++n)
      for (std::size_t i = 0; i < modes.size(); ++i)
        slab_gain[n * modes.size() + i] = -modes.shapes(Eigen::Index(3 * n + 2), Eigen::Index(i));
  }
  std::vector<double> slab_out(total, 0.0);
  renderBody(modes, slab_gain, e.slab_node, e.impulse_ns, o.sample_rate_hz, modes.size(), slab_out);

  // The pen receives +J along the surface normal, which in the pen's frame (axis +z from the tip,
  // tilted about y) is (sin tilt, 0, cos tilt).
  std::vector<double> pen_out(total, 0.0);
  if (pen && pen->mesh && pen->modes && pen->modes->size() > 0) {
    const AudibleModes& pm = *pen->modes;
    const double tilt = pen->tilt_deg * std::numbers::pi / 180.0;
    const Eigen::Vector3d d(std::sin(tilt), 0.0, std::cos(tilt));
    std::vector<double> pen_gain(pm.size());
    for (std::size_t i = 0; i < pm.size(); ++i)
      pen_gain[i] = pm.shapes.block(3 * pen->tip_node, Eigen::Index(i), 3, 1).col(0).dot(d);
    const std::vector<int> tip(total, 0);
    renderBody(pm, pen_gain, tip, e.impulse_ns, o.sample_rate_hz, pm.size(), pen_out);
  }

  out.displacement.resize(total);
  for (std::size_t n = 0; n < total; ++n) {
    out.displacement[n] = slab_out[n] + pen_out[n];
    out.slab_peak = std::max(out.slab_peak, std::fabs(slab_out[n]));
    out.pen_peak = std::max(out.pen_peak, std::fabs(pen_out[n]));
  }
  return out;
}

void normaliseScrape(ScrapeRender& out, double peak) {
  const std::vector<double>& d = out.displacement;
  out.raw_peak = 0.0;
  out.raw_rms = 0.0;
  for (double x : d) {
    out.raw_peak = std::max(out.raw_peak, std::fabs(x));
    out.raw_rms += x * x;
  }
  out.raw_rms = d.empty() ? 0.0 : std::sqrt(out.raw_rms / double(d.size()));
  const double gain = out.raw_peak > 0 ? peak / out.raw_peak : 0.0;
  out.samples.resize(d.size());
  for (std::size_t n = 0; n < d.size(); ++n) out.samples[n] = float(d[n] * gain);
}

ScrapeRender renderScrape(const tex::TextureMap& map, const TetMesh& slab, const AudibleModes& modes,
                          std::span<const ScrapeSample> path, const ScrapeOptions& o, const PenModes* pen) {
  ScrapeRender out = scrapeDisplacement(map, slab, modes, path, o, pen);
  normaliseScrape(out, o.peak);
  return out;
}

}  // namespace thx::audio
