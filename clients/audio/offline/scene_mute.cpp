#include "clients/audio/offline/scene_mute.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace thx::audio {

std::vector<MutedSpan> mutedSpans(std::span<const SceneStart> hellos, const std::string& first_scene,
                                  const std::function<bool(const std::string&)>& muted) {
  std::map<std::string, bool> known;
  const auto is_muted = [&](const std::string& name) {
    auto it = known.find(name);
    if (it == known.end()) it = known.emplace(name, muted(name)).first;
    return it->second;
  };
  std::vector<MutedSpan> out;
  std::string current = first_scene;
  bool open = is_muted(current);
  if (open) out.push_back({std::numeric_limits<std::int64_t>::min(), std::numeric_limits<std::int64_t>::max(), current});
  for (const SceneStart& h : hellos) {
    if (h.scene_name.empty() || h.scene_name == current) continue;  // as renderScrapeSession
    current = h.scene_name;
    const bool now = is_muted(current);
    if (open && !now) out.back().to_utime = h.utime;
    if (!open && now) out.push_back({h.utime, std::numeric_limits<std::int64_t>::max(), current});
    open = now;
  }
  return out;
}

std::size_t silenceMuted(std::vector<float>& samples, std::span<const MutedSpan> spans, std::int64_t origin_utime,
                         double sample_rate_hz) {
  const auto first_sample_at_or_after = [&](std::int64_t utime) -> std::int64_t {
    if (utime == std::numeric_limits<std::int64_t>::min()) return 0;
    if (utime == std::numeric_limits<std::int64_t>::max()) return std::int64_t(samples.size());
    const double n = std::ceil(double(utime - origin_utime) * 1e-6 * sample_rate_hz - 1e-9);
    return std::clamp<std::int64_t>(std::int64_t(n), 0, std::int64_t(samples.size()));
  };
  std::size_t zeroed = 0;
  for (const MutedSpan& s : spans) {
    const std::int64_t a = first_sample_at_or_after(s.from_utime), b = first_sample_at_or_after(s.to_utime);
    if (b <= a) continue;
    std::fill(samples.begin() + a, samples.begin() + b, 0.0f);
    zeroed += std::size_t(b - a);
  }
  return zeroed;
}

}  // namespace thx::audio
