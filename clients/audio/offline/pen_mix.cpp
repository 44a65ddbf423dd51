#include "clients/audio/offline/pen_mix.hpp"

namespace thx::audio {

ScrapeSessionRender renderPenMix(std::span<const PenPath> pens, std::span<const SceneStart> hellos,
                                 const std::string& first_scene, const PenSurfaceFor& surface_for, std::int64_t origin_tick) {
  ScrapeSessionRender out;
  double peak = 0.0;
  bool first = true;
  for (const PenPath& pen : pens) {
    if (pen.samples.empty()) continue;
    const auto surface = [&](const std::string& name) -> const ScrapeSurface& { return surface_for(name, pen.device); };
    if (first) peak = surface(first_scene).options.peak;
    ScrapeSessionRender one = scrapeSessionDisplacement(pen.samples, hellos, first_scene, surface, origin_tick);
    if (first) out.render = std::move(one.render);  // one pen: its own sum, untouched
    else addScrape(out.render, one.render);
    if (one.scenes.size() > out.scenes.size()) out.scenes = std::move(one.scenes);
    first = false;
  }
  if (!first) normaliseScrape(out.render, peak);
  return out;
}

}  // namespace thx::audio
