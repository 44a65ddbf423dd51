#include "clients/audio/scrape_synthesis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "clients/audio/meso_impulses.hpp"
#include "clients/audio/relief_impulses.hpp"
#include "clients/audio/resonator_bank.hpp"

namespace thx::audio {
namespace {

ReliefTick reliefTick(const ScrapeSample& s) { return {s.in_contact, s.n_geom, s.n_contact, s.v_tangent}; }

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

ScrapeExcitation scrapeExcitation(const tex::TextureMap& map, const TetMesh& slab, std::span<const ScrapeSample> path,
                                  const ScrapeOptions& o) {
  ScrapeExcitation e;
  if (path.empty()) return e;
  std::vector<int> top;
  for (std::size_t n = 0; n < slab.nodes.size(); ++n)
    if (std::fabs(slab.nodes[n].z()) < 1e-12) top.push_back(int(n));

  const std::int64_t first_tick = path.front().tick;
  auto sampleOf = [&](std::int64_t tick) {
    return std::size_t(std::llround(double(tick - first_tick) / o.servo_hz * o.sample_rate_hz));
  };
  const double last_s = double(path.back().tick - first_tick) / o.servo_hz;
  const std::size_t total = std::size_t(std::ceil((last_s + o.tail_s) * o.sample_rate_hz)) + 1;
  e.impulse_ns.assign(total, 0.0);
  e.slab_node.assign(total, top.empty() ? 0 : top.front());
  if (top.empty()) return e;
  const SlabTopFace top_face(slab, o.surface_size_m);

  const bool micro = o.roughness.amplitude > 0.0;
  const RoughnessProfile profile(micro ? o.roughness : RoughnessOptions{});
  std::vector<double> force;
  double distance_m = 0.0, micro_power = 0.0;
  std::size_t micro_samples = 0;

  MesoSurface surface{&map, tex::Address::Wrap, {0, 0, 1}, o.pen_mass_kg, 0.05};
  MesoState state;
  bool continuing = false;  // the previous segment was in contact and owns sample at_a
  for (std::size_t k = 1; k < path.size(); ++k) {
    const ScrapeSample &a = path[k - 1], &b = path[k];
    if (!a.in_contact || !b.in_contact || b.tick <= a.tick) {
      state = {};  // lifted: the next touch starts a new walk
      continuing = false;
      continue;
    }
    const std::size_t at_a = std::min(sampleOf(a.tick), total - 1), at_b = std::min(sampleOf(b.tick), total - 1);
    const int node = top_face.nearest(b.uv);
    for (std::size_t n = continuing ? at_a + 1 : at_a; n <= at_b; ++n) e.slab_node[n] = node;
    continuing = true;

    // Meso: the pen's momentum change at the sample of the tick that entered the texel.
    if (o.meso == MesoSource::TexelWalk) {
      const double dt = double(b.tick - a.tick) / o.servo_hz;
      // Velocity in the texture's tangent frame: +x along u, +y along v.
      const Eigen::Vector3d v((b.uv.u - a.uv.u) * o.surface_size_m.x() / dt,
                              (b.uv.v - a.uv.v) * o.surface_size_m.y() / dt, 0);
      mesoImpulsesAlong(surface, state, a.uv, b.uv, v, [&](const MesoImpulse& m) {
        e.impulse_ns[at_b] += m.impulse.z();
        ++e.impulses;
        e.nonzero_impulses += m.impulse.z() != 0.0;
      });
    } else {
      const double j = reliefImpulse(reliefTick(a), reliefTick(b), o.pen_mass_kg);
      e.impulse_ns[at_b] += j;
      ++e.impulses;
      e.nonzero_impulses += j != 0.0;
    }

    // Micro: the force of the samples from tick a up to tick b, read along the travelled distance.
    const double step_m = Eigen::Vector2d((b.uv.u - a.uv.u) * o.surface_size_m.x(),
                                          (b.uv.v - a.uv.v) * o.surface_size_m.y()).norm();
    if (micro && at_b > at_a) {
      force.assign(at_b - at_a, 0.0);
      microForce(profile, distance_m, distance_m + step_m, a.f_normal_n, b.f_normal_n, force);
      for (std::size_t n = 0; n < force.size(); ++n) {
        e.impulse_ns[at_a + n] += force[n] / o.sample_rate_hz;
        micro_power += force[n] * force[n];
      }
      micro_samples += force.size();
    }
    distance_m += step_m;
  }
  e.micro_rms_n = micro_samples ? std::sqrt(micro_power / double(micro_samples)) : 0.0;
  return e;
}

ScrapeRender renderScrape(const tex::TextureMap& map, const TetMesh& slab, const AudibleModes& modes,
                          std::span<const ScrapeSample> path, const ScrapeOptions& o, const PenModes* pen) {
  ScrapeRender out;
  if (path.empty()) return out;
  const ScrapeExcitation e = scrapeExcitation(map, slab, path, o);
  out.impulses = e.impulses;
  out.nonzero_impulses = e.nonzero_impulses;
  out.micro_rms_n = e.micro_rms_n;
  const std::size_t total = e.impulse_ns.size();

  // The slab receives -J along its top face's normal (+z): the gain of each mode at each node.
  std::vector<double> slab_gain(slab.nodes.size() * modes.size());
  for (std::size_t n = 0; n < slab.nodes.size(); ++n)
    for (std::size_t i = 0; i < modes.size(); ++i)
      slab_gain[n * modes.size() + i] = -modes.shapes(Eigen::Index(3 * n + 2), Eigen::Index(i));
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

  std::vector<double> rendered(total);
  for (std::size_t n = 0; n < total; ++n) {
    rendered[n] = slab_out[n] + pen_out[n];
    out.slab_peak = std::max(out.slab_peak, std::fabs(slab_out[n]));
    out.pen_peak = std::max(out.pen_peak, std::fabs(pen_out[n]));
    out.raw_peak = std::max(out.raw_peak, std::fabs(rendered[n]));
    out.raw_rms += rendered[n] * rendered[n];
  }
  out.raw_rms = std::sqrt(out.raw_rms / double(total));
  const double gain = out.raw_peak > 0 ? o.peak / out.raw_peak : 0.0;
  out.samples.resize(total);
  for (std::size_t n = 0; n < total; ++n) out.samples[n] = float(rendered[n] * gain);
  return out;
}

}  // namespace thx::audio
