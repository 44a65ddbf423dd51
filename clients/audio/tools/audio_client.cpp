// audio-client: the pens scraping a scene's surface, live from hapticd (live_audio.hpp) or
// rendered from a recorded hapticd session to a WAV file (kHelp below).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "clients/audio/analysis/scene_bodies.hpp"
#include "clients/audio/live/audio_output.hpp"
#include "clients/audio/live/live_audio.hpp"
#include "clients/audio/offline/pen_mix.hpp"
#include "clients/audio/offline/physics_sound.hpp"
#include "clients/audio/offline/scene_mute.hpp"
#include "clients/audio/offline/scrape_session.hpp"
#include "clients/audio/offline/scrape_synthesis.hpp"
#include "clients/audio/synthesis/sounding_scene.hpp"
#include "clients/audio/synthesis/surface_sound.hpp"
#include "clients/audio/tools/session_pens.hpp"
#include "base/program_main.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/surface_texture.hpp"
#include "textures/smoothing.hpp"
#include "thx_client/devices.hpp"
#include "thx_client/logged_scene.hpp"

namespace {

using namespace thx::audio;

const char* const kHelp = R"(usage: audio-client --scene FILE [--wav FILE] [live options]             (live)
       audio-client --scene FILE --replay-log FILE --wav FILE [options]      (offline)

The pen scraping the scene's surface, and the physics client's objects. Both sides of every
contact sound: the surface slab's modes (surface.thickness, surface.held), the pen's own
(device.pen: a cylinder, struck at its tip) and each moving object's. The pen: meso level, on a
normal map Eq. 5 at every texel the tip enters (the pen's effective mass, the texel's own
normal), on a relief map the change of the contact normal from tick to tick (a flat map is
silent at this level); micro level, the surface's fractal roughness (surface.roughness) read
along the distance travelled, scaled by the normal force. The physics client's streams: impacts
(the impulse on both bodies' modes at the contact point, over a Hertz contact time from both
sides: an object on the surface, two objects, an object on the pen at its tip), rolling and
sliding objects' texel paths (Eq. 5 on a normal map; on a relief map the change of the object's
normal momentum between contact reports), on the surface and the object; two objects rolling
or sliding on each other (the micro level: the roughness read along the contact's travel, scaled
by the normal force, on both objects, quieter when rolling). Live and offline play
the same excitations through the same code. A mesh surface (surface.mesh) sounds as the solid its
mesh encloses, filled with tetrahedra by Gmsh (a built-in shape at no more than 48 segments): the
pen strikes its surface node nearest the tip along that node's outward normal, the physics
client's contacts strike it at their points.

Live (the default; docs/audio.md "Live audio"): hapticd's CONTACT stream, batched (every servo
tick), of every device's pen, mixed (--device N: pen N alone), through the client kit,
and the physics client's THX_PHYSICS_POSES/IMPACT/CONTACTS. The events go through a lock-free
queue to the audio callback, which places each at its sample (the tick's time plus the playout
delay), renders the micro level sample by sample, and lowers the number of modes it synthesises
when its cost per block nears the block period. Output through RtAudio when a sound device
exists; when none does, one line says so and a timer-driven callback writes the sound to --wav.
Follows hapticd's scene switches (finds NAME.yaml in --scenes-dir).

Offline (--replay-log): deterministic, from a recorded session (`hapticd --record FILE`: one
contact_t per servo tick and device on THX_CONTACT). Every device's pen sounds, mixed: each pen's
scrape (its own walk, its own pen's modes and mass) on the same surface's modes, the sums added
(--device N: pen N alone, on the same timeline as the mix). If the log also holds the physics
client's streams (`physics-client --replay-log SESSION --record FILE`:
THX_PHYSICS_POSES/IMPACT/CONTACTS on the session's clock), they sound too, on the same clock. A
THX_HELLO naming another scene (hapticd --record writes one at each switch) switches to
NAME.yaml (--scenes-dir) from its utime on: the pen's CONTACT samples after it scrape that scene's
surface and pen (the walk starts afresh), the physics streams strike its bodies; bodies struck
before ring on. Each scene loaded must have the texture fingerprint the log's hellos give it (else
an error naming the log, the scene and both fingerprints; --allow-different-scene renders anyway,
with a warning). While a scene with `audio: {mute: true}` runs the output is exact silence (live:
from the switch to it, nothing is synthesised; offline: the render's samples from its hello to the
next unmuted scene's are zeroed); the sound comes back with the next unmuted scene. The sum of the
modal displacements as a 32-bit float WAV normalised to a peak of 0.5 (-6 dBFS), or times --gain.

  --scene FILE           the scene hapticd runs (docs/scenes.md)
  --replay-log FILE      offline: hapticd's --record log, or physics-client's --record log (with
                         or without a hapticd session in it)
  --wav FILE             output (offline: required; live: written when no device plays)
  --slab-thickness M     the surface slab's thickness (default: the scene's surface.thickness)
  --slab-cells N         Tet10 cells per side of the slab, in the plane (default 20)
  --slab-layers N        Tet10 cells through the slab's thickness (default 2)
  --clamp-edges          hold the slab at its four sides (default: the scene's surface.held)
  --modes N              elastic modes computed (default 40)
  --pen-mass KG          the mass in Eq. 5 (default: the simulated device's mass)
  --sample-rate HZ       default 44100
  --tail S               offline: ring-out after the last tick (default 0.5)
  --device N             the pen of device N alone (its index in hello_t.device_names; offline:
                         default every pen, mixed; the physics streams sound either way; live:
                         likewise, default every pen the scene has, mixed)
  --gain G               offline: output = G x, x what the bodies' listeners hear (m^3), neither
                         normalised nor clamped (renders of one session at one gain compare sample
                         for sample: a pen alone against the mix); live: output = clamp(G x, -1, 1)
                         (default 5e6)
  --cache-dir DIR        modal cache (default as modal-analyze); --no-cache: none
  --scenes-dir DIR       where a switched-to scene NAME.yaml is found (offline default: --scene's
                         folder; live default: scenes)
  --no-pen               the slab alone sounds (not the pen's own modes)
  --no-micro             no micro-level roughness (meso impulses only; no object contacts either)
  --no-object-contacts   no sound from lasting contacts between two objects (rolling or sliding
                         on each other: the micro level on both, docs/audio.md §10a)
  --object-elements E    tet10 (default) or tet4: the moving objects' elements
  --allow-different-scene  play although hapticd runs another scene, or the log's hellos give the
                         scene another texture fingerprint (a warning)
Live:
  --lcm-url URL          LCM bus (default the kit's)
  --connect-timeout S    wait this long for hapticd's hello (default 10)
  --batch-rate HZ        CONTACT batches per second (default 200; every tick either way)
  --playout-ms MS        an impulse sounds this long after its tick (default: a batch period
                         plus a block, so the ticks of one batch keep their spacing)
  --block N              frames per callback block (default 256, at most 4096)
  --output MODE          auto (a device, else timer + WAV; default), device, timer
  --audio-api API        alsa, pulse or jack (default: ALSA, then PulseAudio)
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
  bool no_pen = false, no_micro = false, no_object_contacts = false;
  ElementOrder object_order = ElementOrder::Quadratic;
  std::optional<std::string> scenes_dir;
  std::optional<int> device;  // offline: one pen alone (default every pen); live: the pen played
  std::optional<double> gain;  // offline: G x instead of normalising; live: LiveOptions::gain
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
    else if (a == "--slab-layers") o.slab.layers = int(thx::cli::parseInteger(a, value(), 1, 40));
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
    else if (a == "--scenes-dir") o.scenes_dir = value();
    else if (a == "--no-pen") o.no_pen = true;
    else if (a == "--no-micro") o.no_micro = true;
    else if (a == "--no-object-contacts") o.no_object_contacts = true;
    else if (a == "--object-elements") {
      const std::string e = value();
      if (e != "tet4" && e != "tet10") throw thx::UsageError("--object-elements: expected tet4 or tet10, got '" + e + "'");
      o.object_order = e == "tet4" ? ElementOrder::Linear : ElementOrder::Quadratic;
    }
    else if (a == "--batch-rate") o.live.batch_hz = thx::cli::parseNumber(a, value(), {1, 100000, true, "Hz"});
    else if (a == "--playout-ms") o.playout_ms = thx::cli::parseNumber(a, value(), {0, 10000, false, "ms"});
    else if (a == "--block") o.live.block_frames = std::size_t(thx::cli::parseInteger(a, value(), 16, long(kMaxBlockFrames)));
    else if (a == "--output") {
      o.live.output = value();
      if (o.live.output != "auto" && o.live.output != "device" && o.live.output != "timer")
        throw thx::UsageError("--output: expected auto, device or timer, got '" + o.live.output + "'");
    } else if (a == "--audio-api") o.live.audio_api = value();
    else if (a == "--gain") o.gain = thx::cli::parseNumber(a, value(), {0, 1e12, false, ""});
    else if (a == "--device") o.device = int(thx::cli::parseInteger(a, value(), 0, thx::client::kMaxDevices - 1));
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

// The raw (not normalised) energy of the physics streams' modal displacements: the sum of their
// squares over the sample rate (m² s), comparable between renders of different lengths.
double energyOf(const std::vector<double>& x, double sample_rate_hz) {
  double e = 0.0;
  for (double v : x) e += v * v;
  return e / sample_rate_hz;
}

// One scene as the offline render plays it: the surface (texture, slab, modes) and each device's
// pen the scrapes use (by device index: its own pen's modes and Eq. 5 mass, the same surface); the
// physics streams share the slab's modes.
struct OfflineScene {
  SurfaceSound surface;
  std::vector<PenSound> pens;
  std::vector<PenModes> pen_views;   // point into `pens`
  std::vector<ScrapeSurface> scrapes;  // point into `surface` and `pen_views`
  std::shared_ptr<const ModalBody> slab_body;
};

int runOffline(const Options& o) {
  const auto stem = [](const std::string& file) { return std::filesystem::path(file).stem().string(); };
  const std::string first_name = stem(o.scene);
  const std::string dir = o.scenes_dir ? *o.scenes_dir : std::filesystem::path(o.scene).parent_path().string();
  const auto file_of = [&](const std::string& name) {
    if (name == first_name) return o.scene;
    return (std::filesystem::path(dir.empty() ? "." : dir) / (name + ".yaml")).string();
  };
  // Each scene the log names is loaded and analysed once, when first needed (cache §2).
  std::map<std::string, std::unique_ptr<OfflineScene>> scenes;
  // hapticd --record's hellos carry the texture's fingerprint: each scene loaded must be the one
  // recorded (thx_client/logged_scene.hpp).
  const std::vector<thx::client::LoggedScene> logged = thx::client::loggedScenes(o.log);
  const auto offline_scene = [&](const std::string& name) -> OfflineScene& {
    std::unique_ptr<OfflineScene>& slot = scenes[name];
    if (slot) return *slot;
    const auto check = [&](const thx::scene::SceneSurface& s) {
      const std::string warning = thx::client::checkLoggedScene(logged, {name, s.fingerprint}, o.log, o.live.allow_different_scene);
      if (!warning.empty()) std::fprintf(stderr, "audio-client: warning: %s\n", warning.c_str());
    };
    // Offline, a mesh scene sounds as the solid its mesh encloses (Gmsh: this program links it).
    const MeshBodyBuilder mesh_body = [](const thx::scene::Scene& s) { return meshSurfaceBody(s); };
    auto sc = std::make_unique<OfflineScene>(OfflineScene{buildSurfaceSound(file_of(name), o.slab, check, mesh_body), {}, {}, {}, nullptr});
    const thx::scene::Scene& scene = sc->surface.scene;
    const std::size_t devices = thx::scene::deviceCount(scene);
    sc->pens.resize(devices);
    sc->pen_views.resize(devices);
    for (std::size_t d = 0; d < devices; ++d) {
      if (!o.no_pen) sc->pens[d] = buildPenSound(thx::scene::sceneForDevice(scene, d), o.slab);
      sc->pen_views[d] = PenModes{&sc->pens[d].mesh, &sc->pens[d].modes, sc->pens[d].tip_node, sc->pens[d].tilt_deg};
      ScrapeSurface surface;
      ScrapeOptions& so = surface.options;
      so.sample_rate_hz = o.slab.sample_rate_hz;
      so.servo_hz = scene.rates.servo_hz;
      so.pen_mass_kg = o.pen_mass ? *o.pen_mass : thx::scene::deviceAt(scene, d).sim.device_mass_kg;
      so.surface_size_m = scene.surface.size_m;
      so.tail_s = o.tail;
      so.meso = sc->surface.map().isRelief() ? MesoSource::ContactNormals : MesoSource::TexelWalk;
      so.roughness = sceneRoughness(scene);
      if (o.no_micro) so.roughness.amplitude = 0.0;
      so.mesh_to_world = sc->surface.mesh_to_world;  // a mesh scene: the scrape strikes its solid's surface
      surface.map = &sc->surface.map();
      surface.slab = &sc->surface.slab;
      surface.modes = &sc->surface.modes;
      surface.pen = o.no_pen ? nullptr : &sc->pen_views[d];
      sc->scrapes.push_back(surface);
    }
    sc->slab_body = std::make_shared<const ModalBody>(sc->surface.slab, sc->surface.modes);
    if (sc->surface.mesh_to_world)
      std::printf("audio-client: %s: a mesh surface: the pen and the physics client's contacts strike the solid its mesh "
                  "encloses\n",
                  name.c_str());
    slot = std::move(sc);
    return *slot;
  };

  // Every device's pen scrapes (or --device's alone), sample 0 at the session's first tick.
  const SessionPens pens = readSessionPens(o.log, o.device);
  const PhysicsStreams physics = readPhysicsStreams(o.log);
  if (!pens.origin_tick && physics.empty())
    throw thx::Error(thx::Error::Kind::Io, o.log + ": no THX_CONTACT or THX_PHYSICS_* events (not a hapticd or physics-client --record log?)");
  std::vector<SceneStart> hellos;
  for (const auto& h : physics.hellos) hellos.push_back({h.utime, h.scene_name});

  OfflineScene& first = offline_scene(first_name);
  // The pens' scrapes, each stretch between switches on its own scene's surface, summed.
  const auto scrape_for = [&](const std::string& name, int device) -> const ScrapeSurface& {
    const OfflineScene& sc = offline_scene(name);
    if (std::size_t(device) >= sc.scrapes.size())
      throw thx::Error(thx::Error::Kind::Config, o.log + ": device " + std::to_string(device) + " scrapes scene '" + name +
                                                     "', which has " + std::to_string(sc.scrapes.size()) +
                                                     " device(s) (its pen and mass are unknown)");
    return sc.scrapes[std::size_t(device)];
  };
  ScrapeSessionRender session = renderPenMix(pens.pens, hellos, first_name, scrape_for, pens.origin_tick.value_or(0));
  ScrapeRender& r = session.render;
  const ScrapeOptions& so = first.scrapes.front().options;
  const std::int64_t origin = pens.origin_utime ? *pens.origin_utime : physics.firstUtime();
  std::vector<double> physics_sum;  // the physics streams' listeners' sum (m^3), for --gain
  if (!physics.empty()) {
    const BodyOptions bo = bodyOptions(o.slab, o.object_order);
    const auto sounding = [&](const std::string& name) {
      OfflineScene& sc = offline_scene(name);
      SoundingScene s =
          soundingScene(name, sc.surface.scene, sc.surface.map().isRelief(), bo, sc.slab_body, sc.surface.mesh_to_world);
      setPenBody(s, sc.pens.front());  // impacts with the pen ring device 0's pen
      return s;
    };
    PhysicsSoundOptions po;
    po.sample_rate_hz = o.slab.sample_rate_hz;
    po.tail_s = o.tail;
    po.object_contacts.enabled = !o.no_micro && !o.no_object_contacts;
    PhysicsRender pr = renderPhysicsStreams(physics, sounding(first_name), sounding, origin, po);
    r.samples = mixSessionSound(r.samples, r.raw_peak / so.peak, pr.samples, so.peak);
    physics_sum = std::move(pr.samples);
    std::printf("audio-client: %s: physics: %zu impacts (%zu between two objects; contact %.3g-%.3g ms), %zu meso "
                "impulses, %zu relief impulses, %zu object-contact segments, physics energy %.4g m2 s, scenes:",
                o.log.c_str(), pr.impacts, pr.object_impacts, pr.min_contact_s * 1e3, pr.max_contact_s * 1e3,
                pr.meso_impulses, pr.relief_impulses, pr.object_contact_segments, energyOf(physics_sum, o.slab.sample_rate_hz));
    for (const std::string& n : pr.scenes) std::printf(" %s", n.c_str());
    std::printf("\n");
  }
  // --gain: the listeners' sums at a fixed gain instead of normalised (a pen alone against the mix).
  if (o.gain) r.samples = scaledSessionSound(r.displacement, physics_sum, *o.gain);
  // A muted scene (audio.mute) is exact silence for as long as it runs; normalised before, so the
  // unmuted stretches sound as they would without the muted ones' silence.
  const std::vector<MutedSpan> muted = mutedSpans(hellos, first_name, [&](const std::string& name) {
    return name == first_name ? first.surface.scene.audio.mute : thx::scene::loadScene(file_of(name)).audio.mute;
  });
  if (!muted.empty()) {
    const std::size_t zeroed = silenceMuted(r.samples, muted, origin, o.slab.sample_rate_hz);
    std::printf("audio-client: %s: muted scenes (audio.mute):", o.log.c_str());
    for (const MutedSpan& m : muted) std::printf(" %s", m.scene.c_str());
    std::printf(", %zu samples of silence\n", zeroed);
  }
  WavWriter(o.wav, int(o.slab.sample_rate_hz)).write(r.samples);
  if (pens.pens.size() > 1 || o.device) {
    std::printf("audio-client: %s: %s:", o.log.c_str(), o.device ? "one pen alone" : "every pen, mixed");
    for (const PenPath& p : pens.pens) std::printf(" device %d (%zu ticks)", p.device, p.samples.size());
    std::printf("\n");
  }
  if (session.scenes.size() > 1) {
    std::printf("audio-client: %s: the pen's scrape in %zu stretches, scenes:", o.log.c_str(), session.scenes.size());
    for (const std::string& n : session.scenes) std::printf(" %s", n.c_str());
    std::printf("\n");
  }
  std::printf("audio-client: %s: %zu ticks, %zu %s impulses (%zu non-zero), micro force RMS %.3g N, %zu slab + %zu pen modes "
              "(peaks %.3g / %.3g, RMS %.3g), %.2f s -> %s\n",
              o.log.c_str(), pens.ticks(), r.impulses, so.meso == MesoSource::TexelWalk ? "meso" : "relief", r.nonzero_impulses,
              r.micro_rms_n, first.surface.modes.size(), first.pens.front().modes.size(), r.slab_peak, r.pen_peak,
              r.raw_rms, double(r.samples.size()) / o.slab.sample_rate_hz, o.wav.c_str());
  return 0;
}

int run(Options o) {
  if (!o.log.empty()) return runOffline(o);
  LiveOptions& l = o.live;
  l.scene = o.scene;
  l.wav = o.wav;
  l.scene_settings.slab = o.slab;
  l.scene_settings.device = o.device.value_or(0);
  l.scene_settings.every_device = !o.device;  // every pen unless --device names one
  if (o.gain) l.gain = *o.gain;
  l.scene_settings.slab.quiet = l.quiet;
  l.scene_settings.pen_mass_kg = o.pen_mass;
  l.scene_settings.pen_modes = !o.no_pen;
  l.scene_settings.micro = !o.no_micro;
  l.scene_settings.object_contacts = !o.no_object_contacts;
  l.scene_settings.object_order = o.object_order;
  l.scene_settings.mesh_body = [](const thx::scene::Scene& s) { return meshSurfaceBody(s); };  // Gmsh: this program links it
  if (o.scenes_dir) l.scenes_dir = *o.scenes_dir;
  const double playout_ms = o.playout_ms ? *o.playout_ms : 1e3 / l.batch_hz + 1e3 * double(l.block_frames) / o.slab.sample_rate_hz;
  l.scene_settings.playout_delay_ns = std::int64_t(std::llround(playout_ms * 1e6));
  return runLive(l);
}

}  // namespace

int main(int argc, char** argv) {
  return thx::runProgram("audio-client", kHelp, argc, argv,
                             [](const std::vector<std::string>& args) { return run(parse(args)); });
}
