#include "clients/audio/offline/scrape_session.hpp"

#include <algorithm>
#include <cmath>

namespace thx::audio {

namespace {

struct Stretch {
  std::string scene;
  std::vector<ScrapeSample> path;
};

// The samples split by scene: a hello switches at its utime (the samples are in log order).
std::vector<Stretch> stretches(std::span<const TimedScrapeSample> samples, std::span<const SceneStart> hellos,
                               const std::string& first_scene) {
  std::vector<SceneStart> starts;
  std::string current = first_scene;
  for (const SceneStart& h : hellos) {
    if (h.scene_name.empty() || h.scene_name == current) continue;
    current = h.scene_name;
    starts.push_back(h);
  }
  std::vector<Stretch> out{{first_scene, {}}};
  std::size_t next = 0;
  for (const TimedScrapeSample& s : samples) {
    while (next < starts.size() && s.utime >= starts[next].utime) out.push_back({starts[next++].scene_name, {}});
    out.back().path.push_back(s.sample);
  }
  std::erase_if(out, [](const Stretch& s) { return s.path.empty(); });
  return out;
}

}  // namespace

ScrapeSessionRender scrapeSessionDisplacement(std::span<const TimedScrapeSample> samples, std::span<const SceneStart> hellos,
                                              const std::string& first_scene,
                                              const std::function<const ScrapeSurface&(const std::string&)>& surface_for,
                                              std::optional<std::int64_t> origin_tick) {
  ScrapeSessionRender out;
  if (samples.empty()) return out;
  const ScrapeOptions session = surface_for(first_scene).options;
  for (const Stretch& st : stretches(samples, hellos, first_scene)) {
    const ScrapeSurface& surface = surface_for(st.scene);
    ScrapeOptions o = surface.options;
    o.sample_rate_hz = session.sample_rate_hz;
    o.servo_hz = session.servo_hz;  // hapticd's servo keeps its rate across switches
    o.tail_s = session.tail_s;
    // One timeline; a new PenScrape: the walk restarts.
    o.origin_tick = origin_tick ? *origin_tick : samples.front().sample.tick;
    addScrape(out.render, scrapeDisplacement(*surface.map, *surface.slab, *surface.modes, st.path, o, surface.pen));
    out.scenes.push_back(st.scene);
  }
  return out;
}

void addScrape(ScrapeRender& r, const ScrapeRender& part) {
  if (r.displacement.size() < part.displacement.size()) r.displacement.resize(part.displacement.size(), 0.0);
  for (std::size_t n = 0; n < part.displacement.size(); ++n) r.displacement[n] += part.displacement[n];
  r.impulses += part.impulses;
  r.nonzero_impulses += part.nonzero_impulses;
  r.slab_peak = std::max(r.slab_peak, part.slab_peak);
  r.pen_peak = std::max(r.pen_peak, part.pen_peak);
  const std::size_t in_contact = r.micro_samples + part.micro_samples;
  if (r.micro_samples == 0) r.micro_rms_n = part.micro_rms_n;  // exactly the one part's
  else if (part.micro_samples > 0)
    r.micro_rms_n = std::sqrt((r.micro_rms_n * r.micro_rms_n * double(r.micro_samples) +
                               part.micro_rms_n * part.micro_rms_n * double(part.micro_samples)) /
                              double(in_contact));
  r.micro_samples = in_contact;
}

ScrapeSessionRender renderScrapeSession(std::span<const TimedScrapeSample> samples, std::span<const SceneStart> hellos,
                                        const std::string& first_scene,
                                        const std::function<const ScrapeSurface&(const std::string&)>& surface_for) {
  ScrapeSessionRender out = scrapeSessionDisplacement(samples, hellos, first_scene, surface_for);
  if (!samples.empty()) normaliseScrape(out.render, surface_for(first_scene).options.peak);
  return out;
}

}  // namespace thx::audio
