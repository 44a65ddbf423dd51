// audio-client: the pen scraping a scene's surface, live from hapticd (live_audio.hpp) or
// rendered from a recorded hapticd session to a WAV file (kHelp below).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <thx_msgs/contact_t.hpp>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "clients/audio/audio_output.hpp"
#include "clients/audio/live_audio.hpp"
#include "clients/audio/scrape_synthesis.hpp"
#include "clients/audio/surface_sound.hpp"
#include "thx_msgs/log_reader.hpp"

namespace {

using namespace thx::audio;

const char* const kHelp = R"(usage: audio-client --scene FILE [--wav FILE] [live options]             (live)
       audio-client --scene FILE --replay-log FILE --wav FILE [options]      (offline)

The pen scraping the scene's surface. At every texel the pen tip enters, Eq. 5 gives a meso
impulse (the pen's mass, the texel's own normal); it strikes the surface slab's modes (modal
analysis of the scene's surface material, cached like modal-analyze's) at the nearest node of the
slab's top face. A flat map is silent. Not yet: the physics client's impacts, micro-level
roughness, the pen's and the objects' own modes.

Live (the default; docs/audio.md "Live audio"): hapticd's CONTACT stream, batched (every servo
tick), through the client kit, and the physics client's rolling objects (their texel paths on
THX_PHYSICS_CONTACTS: Eq. 5 with each object's mass; its impacts are received, not played). The
impulses go through a lock-free queue to the audio callback, which places each at its sample
(the tick's time plus the playout delay) and lowers the number of modes it synthesises when its
cost per block nears the block period. Output through RtAudio when a sound device exists; when
none does, one line says so and a timer-driven callback writes the sound to --wav. Follows
hapticd's scene switches (finds NAME.yaml in --scenes-dir).

Offline (--replay-log): deterministic, from a session hapticd recorded (`hapticd --record FILE`:
one contact_t per servo tick on THX_CONTACT); the sum of the modal displacements as a 32-bit float
WAV normalised to a peak of 0.5 (-6 dBFS).

  --scene FILE           the scene hapticd runs (docs/scenes.md)
  --replay-log FILE      offline: hapticd's --record log
  --wav FILE             output (offline: required; live: written when no device plays)
  --slab-thickness M     the surface slab's thickness (default 0.01)
  --slab-cells N         Tet10 cells per side of the slab, 1 through its thickness (default 16)
  --clamp-edges          hold the slab at its four sides (default: free)
  --modes N              elastic modes computed (default 40)
  --pen-mass KG          the mass in Eq. 5 (default: the simulated device's mass)
  --sample-rate HZ       default 44100
  --tail S               offline: ring-out after the last tick (default 0.5)
  --cache-dir DIR        modal cache (default as modal-analyze); --no-cache: none
Live:
  --lcm-url URL          LCM bus (default the kit's)
  --connect-timeout S    wait this long for hapticd's hello (default 10)
  --allow-different-scene  play although hapticd runs another scene (a warning)
  --scenes-dir DIR       where a switched-to scene NAME.yaml is found (default scenes)
  --batch-rate HZ        CONTACT batches per second (default 200; every tick either way)
  --playout-ms MS        an impulse sounds this long after its tick (default: a batch period
                         plus a block, so the ticks of one batch keep their spacing)
  --block N              frames per callback block (default 256, at most 4096)
  --output MODE          auto (a device, else timer + WAV; default), device, timer
  --audio-api API        alsa, pulse or jack (default: ALSA, then PulseAudio)
  --gain G               output = clamp(G x, -1, 1), x the modal displacement sum in m (default 8e4)
  --fixed-budget         synthesise every mode always (no quality scaling under load)
  --duration S           stop after S seconds (default: at SIGINT/SIGTERM)
  --stats-json FILE      latency (contact -> callback block) and counters at the end
  --events-csv FILE      every event played: its tick's time, receipt, due time, block start (ns)
  --quiet                no progress lines
  -h, --help             this text
)";

struct Options {
  std::string scene, log, wav;
  SlabSettings slab;
  double tail = 0.5;
  std::optional<double> pen_mass;
  LiveOptions live;
  std::optional<double> playout_ms;
};

Options parse(const std::vector<std::string>& args) {
  Options o;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) throw thx::UsageError(a + ": missing value");
      return args[++i];
    };
    if (a == "--scene") o.scene = value();
    else if (a == "--replay-log") o.log = value();
    else if (a == "--wav") o.wav = value();
    else if (a == "--slab-thickness") o.slab.thickness_m = thx::cli::parseNumber(a, value(), {0, 1, true, "m"});
    else if (a == "--slab-cells") o.slab.cells = int(thx::cli::parseInteger(a, value(), 1, 200));
    else if (a == "--clamp-edges") o.slab.clamp_edges = true;
    else if (a == "--modes") o.slab.modes = int(thx::cli::parseInteger(a, value(), 1, 2000));
    else if (a == "--pen-mass") o.pen_mass = thx::cli::parseNumber(a, value(), {0, 100, true, "kg"});
    else if (a == "--sample-rate") o.slab.sample_rate_hz = thx::cli::parseNumber(a, value(), {8000, 384000, false, "Hz"});
    else if (a == "--tail") o.tail = thx::cli::parseNumber(a, value(), {0, 60, false, "s"});
    else if (a == "--cache-dir") o.slab.cache_dir = value();
    else if (a == "--no-cache") o.slab.no_cache = true;
    else if (a == "--lcm-url") o.live.lcm_url = value();
    else if (a == "--connect-timeout") o.live.connect_timeout_s = thx::cli::parseNumber(a, value(), {0, 3600, true, "s"});
    else if (a == "--allow-different-scene") o.live.allow_different_scene = true;
    else if (a == "--scenes-dir") o.live.scenes_dir = value();
    else if (a == "--batch-rate") o.live.batch_hz = thx::cli::parseNumber(a, value(), {1, 100000, true, "Hz"});
    else if (a == "--playout-ms") o.playout_ms = thx::cli::parseNumber(a, value(), {0, 10000, false, "ms"});
    else if (a == "--block") o.live.block_frames = std::size_t(thx::cli::parseInteger(a, value(), 16, long(kMaxBlockFrames)));
    else if (a == "--output") {
      o.live.output = value();
      if (o.live.output != "auto" && o.live.output != "device" && o.live.output != "timer")
        throw thx::UsageError("--output: expected auto, device or timer, got '" + o.live.output + "'");
    } else if (a == "--audio-api") o.live.audio_api = value();
    else if (a == "--gain") o.live.gain = thx::cli::parseNumber(a, value(), {0, 1e12, false, ""});
    else if (a == "--fixed-budget") o.live.adapt_budget = false;
    else if (a == "--duration") o.live.duration_s = thx::cli::parseNumber(a, value(), {0, 1e7, false, "s"});
    else if (a == "--stats-json") o.live.stats_json = value();
    else if (a == "--events-csv") o.live.events_csv = value();
    else if (a == "--quiet") o.live.quiet = true;
    else throw thx::UsageError("unknown option '" + a + "'");
  }
  if (o.scene.empty()) throw thx::UsageError("--scene: missing");
  if (!o.log.empty() && o.wav.empty()) throw thx::UsageError("--wav: missing (--replay-log renders to a WAV)");
  return o;
}

int runOffline(const Options& o) {
  const SurfaceSound sound = buildSurfaceSound(o.scene, o.slab);
  std::vector<ScrapeSample> path;
  thx_msgs::forEachLogMessage<thx_msgs::contact_t>(o.log, "THX_CONTACT", [&](const thx_msgs::contact_t& c, const auto&) {
    path.push_back({c.tick, c.in_contact != 0, {c.uv[0], c.uv[1]}});
  });
  if (path.empty()) throw thx::Error(thx::Error::Kind::Io, o.log + ": no THX_CONTACT events (not a hapticd --record log?)");

  ScrapeOptions so;
  so.sample_rate_hz = o.slab.sample_rate_hz;
  so.servo_hz = sound.scene.rates.servo_hz;
  so.pen_mass_kg = o.pen_mass ? *o.pen_mass : sound.scene.device.sim.device_mass_kg;
  so.surface_size_m = sound.scene.surface.size_m;
  so.tail_s = o.tail;
  const ScrapeRender r = renderScrape(sound.map(), sound.slab, sound.modes, path, so);
  WavWriter(o.wav, int(o.slab.sample_rate_hz)).write(r.samples);
  std::printf("audio-client: %s: %zu ticks, %zu meso impulses, %zu modes, %.2f s -> %s\n", o.log.c_str(), path.size(),
              r.impulses, sound.modes.size(), double(r.samples.size()) / o.slab.sample_rate_hz, o.wav.c_str());
  return 0;
}

int run(Options o) {
  if (!o.log.empty()) return runOffline(o);
  LiveOptions& l = o.live;
  l.scene = o.scene;
  l.wav = o.wav;
  l.scene_settings.slab = o.slab;
  l.scene_settings.slab.quiet = l.quiet;
  l.scene_settings.pen_mass_kg = o.pen_mass;
  const double playout_ms = o.playout_ms ? *o.playout_ms : 1e3 / l.batch_hz + 1e3 * double(l.block_frames) / o.slab.sample_rate_hz;
  l.scene_settings.playout_delay_ns = std::int64_t(std::llround(playout_ms * 1e6));
  return runLive(l);
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  for (const std::string& a : args)
    if (a == "-h" || a == "--help") {
      std::fputs(kHelp, stdout);
      return 0;
    }
  try {
    return run(parse(args));
  } catch (const thx::Error& e) {
    std::fprintf(stderr, "audio-client: %s\n", e.what());
    if (e.kind() == thx::Error::Kind::Usage) std::fprintf(stderr, "(audio-client --help lists the options)\n");
    return thx::exitStatus(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "audio-client: %s\n", e.what());
    return 1;
  }
}
