#pragma once
// The pen's scrape of a whole recorded session across hapticd's scene switches (docs/audio.md
// §5, §11): hapticd's hellos split the CONTACT samples into stretches, one per scene, and each
// stretch is scraped on its own scene's surface (texture, slab modes, pen, Eq. 5 mass,
// roughness), its walk started afresh. All stretches lie on one timeline (sample 0 = the first
// sample's tick, the first scene's servo rate); each slab and pen rings on after its stretch
// ends. Deterministic: the same samples, hellos and surfaces give the same samples.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "clients/audio/offline/scrape_synthesis.hpp"

namespace thx::audio {

// One scene's surface as the pen scrapes it. Not owned; alive during renderScrapeSession.
struct ScrapeSurface {
  const tex::TextureMap* map = nullptr;
  const TetMesh* slab = nullptr;
  const AudibleModes* modes = nullptr;
  const PenModes* pen = nullptr;  // null: the slab alone sounds
  ScrapeOptions options;          // its mass, surface size, meso source, roughness (a mesh scene: its solid's place)
};

struct TimedScrapeSample {
  std::int64_t utime = 0;  // contact_t.utime
  ScrapeSample sample;
};

// hapticd's hello (hello_t): the scene it renders from utime on.
struct SceneStart {
  std::int64_t utime = 0;
  std::string scene_name;
};

struct ScrapeSessionRender {
  ScrapeRender render;              // normalised to the first surface's options.peak
  std::vector<std::string> scenes;  // the scenes of the stretches, in order (repeats kept)
};

// `first_scene` is the scene the session starts in; a hello naming another scene (not empty,
// not the current one) starts a stretch on `surface_for(name)` for the samples with utime at
// or after its own. `surface_for` is called once per stretch and must return a surface that
// stays alive until this returns. Sample rate, servo rate, tail and peak: the first surface's.
ScrapeSessionRender renderScrapeSession(std::span<const TimedScrapeSample> samples, std::span<const SceneStart> hellos,
                                        const std::string& first_scene,
                                        const std::function<const ScrapeSurface&(const std::string&)>& surface_for);

// renderScrapeSession without its normalisation (render.samples empty, the listeners' sum in
// render.displacement), sample 0 at `origin_tick` (unset: the first sample's tick): one pen of
// several on the session's timeline (pen_mix.hpp).
ScrapeSessionRender scrapeSessionDisplacement(std::span<const TimedScrapeSample> samples, std::span<const SceneStart> hellos,
                                              const std::string& first_scene,
                                              const std::function<const ScrapeSurface&(const std::string&)>& surface_for,
                                              std::optional<std::int64_t> origin_tick = {});

// Adds `part` (a render before normalising) to `sum`: the displacement sample by sample (the
// longer length kept), the impulse counts, each body's peak (the larger), the micro level's RMS
// over both parts' samples in contact.
void addScrape(ScrapeRender& sum, const ScrapeRender& part);

}  // namespace thx::audio
