#pragma once
// A simple energy-flux onset detector for rendered audio (the audio tests: clicks in a WAV).
//
// 1. First difference y[n] = x[n] - x[n-1]: tilts the spectrum up by 6 dB/octave, so a struck
//    body's long low modes ringing on do not hide the broadband click of the next strike.
// 2. Energy of y in frames of `frame_s`, every `hop_s`.
// 3. Flux: the rise of the frame energy in dB over the loudest of the frames of the last
//    `lookback_s` (at least the previous one), only where the frame is above `floor_db` below the
//    loudest frame (silence and the last decays carry no onsets). Over the previous frame alone,
//    the beats of a ringing body's close modes rise 3 dB every ~10 ms as it decays and counted as
//    clicks (docs/audio.md §12, "The pen"); a beat never rises above the ring's own last peak.
// 4. An onset is a frame whose flux exceeds `rise_db`; later rising frames within `min_gap_s`
//    belong to the same onset (one click is a short burst of impulses).
// Deterministic. Onset times in seconds, at the centre of the first rising frame.
#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

namespace thx::test {

struct OnsetOptions {
  double frame_s = 0.004;
  double hop_s = 0.002;
  double rise_db = 3.0;
  double floor_db = 50.0;
  double min_gap_s = 0.025;
  double lookback_s = 0.012;  // more than the slab's beat period (~10 ms)
};

inline std::vector<double> detectOnsets(std::span<const float> x, double sample_rate, const OnsetOptions& o = {}) {
  const auto frame = std::size_t(std::llround(o.frame_s * sample_rate)), hop = std::size_t(std::llround(o.hop_s * sample_rate));
  std::vector<double> energy;
  for (std::size_t start = 0; start + frame <= x.size(); start += hop) {
    double e = 0.0;
    for (std::size_t n = std::max<std::size_t>(start, 1); n < start + frame; ++n) {
      const double d = double(x[n]) - double(x[n - 1]);
      e += d * d;
    }
    energy.push_back(e);
  }
  std::vector<double> onsets;
  if (energy.empty()) return onsets;
  const double loudest = *std::max_element(energy.begin(), energy.end());
  if (!(loudest > 0.0)) return onsets;
  const double floor = loudest * std::pow(10.0, -o.floor_db / 10.0);
  const auto lookback = std::max<std::size_t>(1, std::size_t(std::llround(o.lookback_s / o.hop_s)));
  double last = -1e300;
  for (std::size_t k = 1; k < energy.size(); ++k) {
    if (energy[k] < floor) continue;
    double before = floor;
    for (std::size_t j = k > lookback ? k - lookback : 0; j < k; ++j) before = std::max(before, energy[j]);
    const double rise_db = 10.0 * std::log10(energy[k] / before);
    const double t = (double(k * hop) + 0.5 * double(frame)) / sample_rate;
    if (rise_db > o.rise_db && t - last >= o.min_gap_s) {
      onsets.push_back(t);
      last = t;
    }
  }
  return onsets;
}

}  // namespace thx::test
