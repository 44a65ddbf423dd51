#pragma once
// A muted scene (the scene's audio.mute, docs/scenes.md) in an offline render: the spans of a
// session's timeline during which hapticd ran a muted scene, and the render's samples zeroed
// over them, so a muted scene is exact silence (whatever rang before the switch is cut, as the
// live client's scene handoff cuts it) and the sound comes back at the switch to an unmuted one.
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "clients/audio/offline/scrape_session.hpp"

namespace thx::audio {

struct MutedSpan {
  std::int64_t from_utime = std::numeric_limits<std::int64_t>::min();  // inclusive
  std::int64_t to_utime = std::numeric_limits<std::int64_t>::max();    // exclusive
  std::string scene;
};

// The scenes in force as renderScrapeSession splits them (`first_scene` from the start, a hello
// naming another scene from its utime on); those for which muted(name) is true, merged where
// one muted scene follows another. muted() is called once per scene name.
std::vector<MutedSpan> mutedSpans(std::span<const SceneStart> hellos, const std::string& first_scene,
                                  const std::function<bool(const std::string&)>& muted);

// Zeroes samples[n] for every n whose time origin_utime + n / fs (µs) lies in a span. Returns the
// number of samples zeroed.
std::size_t silenceMuted(std::vector<float>& samples, std::span<const MutedSpan> spans, std::int64_t origin_utime,
                         double sample_rate_hz);

}  // namespace thx::audio
