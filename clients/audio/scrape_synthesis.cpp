#include "clients/audio/scrape_synthesis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "clients/audio/pen_scrape.hpp"
#include "clients/audio/resonator_bank.hpp"

namespace thx::audio {
namespace {

struct Strike {
  std::size_t sample;
  int node;
  double impulse_ns;  // along the top face's normal (+z)
};

}  // namespace

ScrapeRender renderScrape(const tex::TextureMap& map, const TetMesh& slab, const AudibleModes& modes,
                          std::span<const ScrapeSample> path, const ScrapeOptions& o) {
  ScrapeRender out;
  if (path.empty()) return out;

  // 1. The impulses, in time order (the same PenScrape the live client runs).
  PenScrape scrape(map, slab, PenScrapeOptions{o.servo_hz, o.pen_mass_kg, o.surface_size_m});
  std::vector<Strike> strikes;
  const std::int64_t first_tick = path.front().tick;
  for (const ScrapeSample& s : path) {
    out.impulses += scrape.next(s, [&](const PenStrike& p) {
      const std::size_t at = std::size_t(std::llround(double(p.tick - first_tick) / o.servo_hz * o.sample_rate_hz));
      strikes.push_back({at, p.node, p.impulse_ns});
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
