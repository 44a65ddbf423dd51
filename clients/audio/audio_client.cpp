// audio-client, offline only (this step): the pen scraping a scene's surface, rendered from a
// recorded hapticd session to a WAV file (kHelp below).
#include <sndfile.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <thx_msgs/contact_t.hpp>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "clients/audio/modal_options.hpp"
#include "clients/audio/scene_bodies.hpp"
#include "clients/audio/physics_sound.hpp"
#include "clients/audio/scrape_synthesis.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/surface_texture.hpp"
#include "textures/smoothing.hpp"
#include "thx_msgs/log_reader.hpp"

namespace {

using namespace thx::audio;

const char* const kHelp = R"(usage: audio-client --scene FILE --replay-log FILE --wav FILE [options]

Offline and deterministic: the pen scraping the scene's surface, from a session hapticd recorded
(`hapticd --record FILE`: one contact_t per servo tick on THX_CONTACT). Meso level: on a normal
map, Eq. 5 at every texel the pen tip enters (the pen's effective mass, the texel's own normal);
on a relief map, the change of the contact normal from tick to tick. Micro level: the surface's
fractal roughness (surface.roughness) read along the distance travelled, scaled by the normal
force. Both sides sound: the surface slab's modes (surface.thickness, surface.held; at the top-face
node nearest the tip) and the pen's own (device.pen: a cylinder, struck at its tip), each from a
modal analysis cached like modal-analyze's.
If the log also holds the physics client's streams (`physics-client --replay-log SESSION --record
FILE`: THX_PHYSICS_POSES/IMPACT/CONTACTS on the session's clock), they sound too, on the same clock:
impacts (the impulse on both bodies' modes at the contact point, over a Hertz contact time),
rolling and sliding objects' texel paths (Eq. 5 on a normal map; on a relief map the change of the
object's normal momentum between contact reports), exciting the surface and the object. A
THX_HELLO naming another scene switches the physics streams to NAME.yaml (--scenes-dir).
The sum of the modal displacements is written as a 32-bit float WAV, normalised to a peak of 0.5
(-6 dBFS).
Not yet: live audio.

  --scene FILE           the scene hapticd ran (docs/scenes.md)
  --replay-log FILE      hapticd's --record log, or physics-client's --record log (with or without
                         a hapticd session in it)
  --wav FILE             output
  --slab-thickness M     the surface slab's thickness (default: the scene's surface.thickness)
  --slab-cells N         Tet10 cells per side of the slab, 1 through its thickness (default 16)
  --clamp-edges          hold the slab at its four sides (default: the scene's surface.held)
  --no-pen               the slab alone sounds (not the pen's own modes)
  --no-micro             no micro-level roughness (meso impulses only)
  --modes N              elastic modes computed (default 40)
  --pen-mass KG          the mass in Eq. 5 (default: the simulated device's mass)
  --sample-rate HZ       default 44100
  --tail S               ring-out after the last tick (default 0.5)
  --cache-dir DIR        modal cache (default as modal-analyze); --no-cache: none
  --object-elements E    tet10 (default) or tet4: the moving objects' elements
  --scenes-dir DIR       where a scene switched to is found as NAME.yaml (default: --scene's folder)
  -h, --help             this text
)";

struct Options {
  std::string scene, log, wav;
  std::optional<double> thickness;
  double sample_rate = 44100, tail = 0.5;
  int cells = 16, modes = 40;
  bool clamp = false, no_cache = false, no_pen = false, no_micro = false;
  std::optional<double> pen_mass;
  std::optional<std::string> cache_dir;
  ElementOrder object_order = ElementOrder::Quadratic;
  std::optional<std::string> scenes_dir;
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
    else if (a == "--slab-thickness") o.thickness = thx::cli::parseNumber(a, value(), {0, 1, true, "m"});
    else if (a == "--slab-cells") o.cells = int(thx::cli::parseInteger(a, value(), 1, 200));
    else if (a == "--clamp-edges") o.clamp = true;
    else if (a == "--no-pen") o.no_pen = true;
    else if (a == "--no-micro") o.no_micro = true;
    else if (a == "--modes") o.modes = int(thx::cli::parseInteger(a, value(), 1, 2000));
    else if (a == "--pen-mass") o.pen_mass = thx::cli::parseNumber(a, value(), {0, 100, true, "kg"});
    else if (a == "--sample-rate") o.sample_rate = thx::cli::parseNumber(a, value(), {8000, 384000, false, "Hz"});
    else if (a == "--tail") o.tail = thx::cli::parseNumber(a, value(), {0, 60, false, "s"});
    else if (a == "--cache-dir") o.cache_dir = value();
    else if (a == "--no-cache") o.no_cache = true;
    else if (a == "--scenes-dir") o.scenes_dir = value();
    else if (a == "--object-elements") {
      const std::string e = value();
      if (e != "tet4" && e != "tet10") throw thx::UsageError("--object-elements: expected tet4 or tet10, got '" + e + "'");
      o.object_order = e == "tet4" ? ElementOrder::Linear : ElementOrder::Quadratic;
    }
    else throw thx::UsageError("unknown option '" + a + "'");
  }
  if (o.scene.empty()) throw thx::UsageError("--scene: missing");
  if (o.log.empty()) throw thx::UsageError("--replay-log: missing (live audio is not implemented yet)");
  if (o.wav.empty()) throw thx::UsageError("--wav: missing");
  return o;
}

void writeWav(const std::string& path, const std::vector<float>& samples, int rate) {
  SF_INFO info{};
  info.samplerate = rate;
  info.channels = 1;
  info.format = SF_FORMAT_WAV | SF_FORMAT_FLOAT;
  SNDFILE* f = sf_open(path.c_str(), SFM_WRITE, &info);
  if (!f) throw thx::Error(thx::Error::Kind::Io, path + ": cannot be written: " + sf_strerror(nullptr));
  // libsndfile's PEAK chunk of a float WAV carries the time of writing: without it, the same
  // samples give the same bytes.
  sf_command(f, SFC_SET_ADD_PEAK_CHUNK, nullptr, SF_FALSE);
  const sf_count_t n = sf_writef_float(f, samples.data(), sf_count_t(samples.size()));
  sf_close(f);
  if (n != sf_count_t(samples.size())) throw thx::Error(thx::Error::Kind::Io, path + ": write failed");
}

int run(const Options& o) {
  const thx::scene::Scene scene = thx::scene::loadScene(o.scene);
  thx::scene::SurfaceTextureOptions to;
  to.smooth = thx::tex::smoothTexture;
  const thx::tex::TextureMap map = thx::scene::buildSurfaceTexture(scene, to);

  std::vector<ScrapeSample> path;
  std::int64_t first_contact_utime = 0;
  thx_msgs::forEachLogMessage<thx_msgs::contact_t>(o.log, "THX_CONTACT", [&](const thx_msgs::contact_t& c, const auto&) {
    if (path.empty()) first_contact_utime = c.utime;
    const auto v3 = [](const double* x) { return Eigen::Vector3d(x[0], x[1], x[2]); };
    path.push_back({c.tick, c.in_contact != 0, {c.uv[0], c.uv[1]}, c.f_normal, v3(c.n_geom_world),
                    v3(c.n_sampled_world), v3(c.v_tangent_world)});
  });
  const PhysicsStreams physics = readPhysicsStreams(o.log);
  if (path.empty() && physics.empty())
    throw thx::Error(thx::Error::Kind::Io, o.log + ": no THX_CONTACT or THX_PHYSICS_* events (not a hapticd or physics-client --record log?)");

  ElasticMaterial material = scene.surface.material;
  SceneMeshOptions mo;
  mo.slab_thickness_m = o.thickness;
  if (o.clamp) mo.clamp_slab = true;
  mo.slab_cells = o.cells;
  TetMesh slab = slabBody(scene, mo).mesh;
  slab.name = "surface (" + scene.surface.material.name + ")";
  ModalSettings ms;
  ms.elastic_modes = o.modes;
  AnalysisOptions ao;
  if (!o.no_cache) ao.cache_dir = o.cache_dir ? *o.cache_dir : defaultModalCacheDir();
  ao.progress = [](const std::string& line) { std::fprintf(stderr, "audio-client: %s\n", line.c_str()); };
  AudibleOptions audible;
  audible.sample_rate_hz = o.sample_rate;
  const AudibleModes modes = audibleModes(analyse(slab, material, ms, ao), material, audible);
  // The pen's own modes (device.pen), struck at its tip.
  const SceneBody pen = penBody(scene);
  const AudibleModes pen_modes =
      o.no_pen ? AudibleModes{} : audibleModes(analyse(pen.mesh, pen.material, ms, ao), pen.material, audible);
  const PenModes pen_view{&pen.mesh, &pen_modes, penTipNode(pen.mesh), scene.device.pen.tilt_deg};

  ScrapeOptions so;
  so.sample_rate_hz = o.sample_rate;
  so.servo_hz = scene.rates.servo_hz;
  so.pen_mass_kg = o.pen_mass ? *o.pen_mass : scene.device.sim.device_mass_kg;
  so.surface_size_m = scene.surface.size_m;
  so.tail_s = o.tail;
  so.meso = map.representation() == thx::tex::Representation::Relief ? MesoSource::ContactNormals : MesoSource::TexelWalk;
  const thx::scene::Roughness& rough = scene.surface.roughness;
  so.roughness.beta = rough.beta;
  so.roughness.amplitude = o.no_micro ? 0.0 : rough.amplitude;
  so.roughness.spacing_m = rough.spacing_m;
  ScrapeRender r = renderScrape(map, slab, modes, path, so, o.no_pen ? nullptr : &pen_view);
  if (!physics.empty()) {
    BodyOptions bo;
    bo.slab_thickness_m = o.thickness;
    bo.slab_cells = o.cells;
    if (o.clamp) bo.clamp_slab = true;
    bo.object_order = o.object_order;
    bo.modal = ms;
    bo.analysis = ao;
    bo.audible = audible;
    const auto stem = [](const std::string& file) { return std::filesystem::path(file).stem().string(); };
    const SoundingScene first =
        soundingScene(stem(o.scene), scene, map.isRelief(), bo, std::make_shared<const ModalBody>(slab, modes));
    const std::string dir = o.scenes_dir ? *o.scenes_dir : std::filesystem::path(o.scene).parent_path().string();
    const auto scene_for = [&](const std::string& name) {
      const std::string file = (std::filesystem::path(dir.empty() ? "." : dir) / (name + ".yaml")).string();
      const thx::scene::Scene next = thx::scene::loadScene(file);
      return soundingScene(name, next, thx::scene::buildSurfaceTexture(next, to).isRelief(), bo);
    };
    PhysicsSoundOptions po;
    po.sample_rate_hz = o.sample_rate;
    po.tail_s = o.tail;
    const std::int64_t origin = path.empty() ? physics.firstUtime() : first_contact_utime;
    const PhysicsRender pr = renderPhysicsStreams(physics, first, scene_for, origin, po);
    r.samples = mixSessionSound(r.samples, r.raw_peak / so.peak, pr.samples, so.peak);
    std::printf("audio-client: %s: physics: %zu impacts (contact %.3g-%.3g ms), %zu meso impulses, %zu relief impulses, scenes:",
                o.log.c_str(), pr.impacts, pr.min_contact_s * 1e3, pr.max_contact_s * 1e3, pr.meso_impulses,
                pr.relief_impulses);
    for (const std::string& n : pr.scenes) std::printf(" %s", n.c_str());
    std::printf("\n");
  }
  writeWav(o.wav, r.samples, int(o.sample_rate));
  std::printf("audio-client: %s: %zu ticks, %zu %s impulses (%zu non-zero), micro force RMS %.3g N, %zu slab + %zu pen modes "
              "(peaks %.3g / %.3g, RMS %.3g), %.2f s -> %s\n",
              o.log.c_str(), path.size(), r.impulses, so.meso == MesoSource::TexelWalk ? "meso" : "relief", r.nonzero_impulses,
              r.micro_rms_n, modes.size(), pen_modes.size(), r.slab_peak, r.pen_peak,
              r.raw_rms, double(r.samples.size()) / o.sample_rate, o.wav.c_str());
  return 0;
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
