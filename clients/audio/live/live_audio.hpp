#pragma once
// audio-client live (docs/audio.md, "Live audio"): hapticd's batched CONTACT (every servo tick)
// and the physics client's contacts and impacts through the client kit, the scene's excitation
// sources, the lock-free queue, the callback (LiveSynth) on a sound device through RtAudio, or,
// where there is none, on a timer thread writing the WAV. Follows hapticd's scene switches.
#include <cstddef>
#include <optional>
#include <string>

#include "clients/audio/live/live_scene.hpp"
#include "clients/audio/live/mode_budget.hpp"

namespace thx::audio {

struct LiveOptions {
  std::string scene;                 // the scene file this client starts with
  std::string scenes_dir = "scenes"; // where a switched-to scene NAME.yaml is found
  LiveSceneSettings scene_settings;  // slab, pen mass, playout delay
  std::string lcm_url;               // "" = the kit's default
  double connect_timeout_s = 10.0;
  bool allow_different_scene = false;
  double batch_hz = 200.0;           // CONTACT batches per second (every tick either way)
  std::size_t block_frames = 256;
  std::string output = "auto";       // auto (a device, else timer + WAV), device, timer
  std::string audio_api;             // "" = ALSA then PulseAudio; alsa, pulse, jack
  std::string wav;                   // where the timer output's sound goes ("" = none)
  double gain = 5e6;                 // output = clamp(gain x, -1, 1), x the listeners' sum in m^3 (docs/audio.md §9a)
  bool adapt_budget = true;
  ModeBudgetOptions budget;
  double duration_s = 0.0;           // 0 = until SIGINT/SIGTERM
  std::string stats_json;            // latency and counters, written at the end
  std::string events_csv;            // one line per event played (its times), for the benchmark
  bool quiet = false;
};

int runLive(const LiveOptions& options);

}  // namespace thx::audio
