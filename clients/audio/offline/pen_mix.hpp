#pragma once
// Every pen of a recorded session, mixed (issue 30; docs/audio.md §5, "Several pens"): hapticd
// serves several devices under one servo clock and records each one's CONTACT samples. Each pen
// scrapes the same surface as one pen does (scrape_session.hpp: its own walk, meso and micro
// levels, its own pen body and Eq. 5 mass, the scene switches), every pen on the session's one
// timeline, and the listeners' sums add before the one normalisation. Modal synthesis is linear,
// so the mix is the sum of the pens rendered alone on that timeline (tests/audio/test_pen_mix.cpp).
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "clients/audio/offline/scrape_session.hpp"

namespace thx::audio {

// One device's CONTACT samples, in log order.
struct PenPath {
  int device = 0;  // its index (hello_t.device_names)
  std::vector<TimedScrapeSample> samples;
};

// A scene's surface as device `device`'s pen scrapes it (its pen's modes, its mass); alive until
// renderPenMix returns.
using PenSurfaceFor = std::function<const ScrapeSurface&(const std::string& scene, int device)>;

// The pens' scrapes summed, sample 0 at `origin_tick` (the session's first tick, whichever pens
// are rendered, so that a pen rendered alone lines up with the mix), normalised to the first
// pen's first surface's options.peak. Counts add; slab_peak and pen_peak are the largest pen's;
// `scenes` are the stretches of the pen that has the most. One pen gives exactly
// renderScrapeSession's samples when `origin_tick` is its first tick.
ScrapeSessionRender renderPenMix(std::span<const PenPath> pens, std::span<const SceneStart> hellos,
                                 const std::string& first_scene, const PenSurfaceFor& surface_for, std::int64_t origin_tick);

}  // namespace thx::audio
