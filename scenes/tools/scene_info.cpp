// scene-info: load scene files exactly as every program does, report errors and warnings, and
// (unless --check) build the surface texture and print what the scene describes.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <variant>
#include <vector>

#include "base/program_main.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_mesh.hpp"
#include "scenes/scene_surface.hpp"
#include "textures/texture_fingerprint.hpp"
#include "textures/smoothing.hpp"
#include "textures/texture_error.hpp"
#include "textures/texture_io.hpp"
#include "textures/texture_stats.hpp"

namespace {

const char* kHelp = R"(usage: scene-info [--check] [--texture-out FILE] SCENE.yaml...

Loads each scene file the way hapticd and the clients will, and prints the first error (with
file, line, field, value and what was expected) or the warnings. Without --check it also builds
the scene's surface texture and prints a summary of the surface, device, script, objects and
rates. Format of scene files: docs/scenes.md.

  --check             only validate (fast; does not build textures)
  --texture-out FILE  write the built surface texture of the (single) scene as a PNG
  -h, --help          this text

Exit status: 0 all scenes valid, 1 a scene has an error, 2 bad command line.
)";

using namespace thx;

double scriptDuration(const scene::Device& device) {
  double total = 0.0;
  for (const scene::ScriptStep& step : device.script) {
    if (const auto* press = std::get_if<scene::PressStep>(&step)) total += press->duration_s;
    if (const auto* hold = std::get_if<scene::HoldStep>(&step)) total += hold->duration_s;
    if (const auto* move = std::get_if<scene::MoveStep>(&step)) total += move->duration_s;
    if (const auto* stroke = std::get_if<scene::StrokeStep>(&step)) {
      total += (stroke->to_m - stroke->from_m).norm() / stroke->speed_m_per_s;
    }
  }
  return total;
}

// surface.mesh: built (read, checked, frames) to report it, as hapticd and visual-client will.
// Prints the mesh; returns its fingerprint with the texture's (what hapticd's hello carries).
std::uint64_t printMesh(const scene::Scene& s, std::uint64_t texture_fingerprint) {
  const scene::MeshSource& m = *s.surface.mesh;
  const auto t0 = std::chrono::steady_clock::now();
  const scene::SceneMesh built = scene::buildSceneMesh(s);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : built.mesh.positions) box.extend(p);
  if (m.kind == scene::MeshSource::Kind::Generator)
    std::printf("mesh:            generator %s, size %.4g m, %d segments\n", m.generator.c_str(), m.size_m, m.segments);
  else
    std::printf("mesh:            file %s, %.4g m per unit\n", m.file.c_str(), m.unit_m);
  std::printf("                 %zu triangles, %zu vertices%s; box [%.4g, %.4g] x [%.4g, %.4g] x [%.4g, %.4g] m (mesh frame);"
              " texture tile %.4g x %.4g m (built in %.0f ms)\n",
              built.mesh.triangles.size(), built.mesh.positions.size(), m.closed ? ", closed" : "", box.min().x(),
              box.max().x(), box.min().y(), box.max().y(), box.min().z(), box.max().z(), built.tile_m.x(),
              built.tile_m.y(), ms);
  return scene::meshSceneFingerprint(texture_fingerprint, built);
}

void printSummary(const scene::Scene& s, const scene::SceneSurface& built, double build_ms) {
  const scene::Surface& surf = s.surface;
  const tex::TextureMap& map = *built.map;
  std::printf("scene:           %s: %s (%s)\n", built.scene_name.c_str(), s.name.c_str(), s.source.c_str());
  std::printf("surface:         %.4g x %.4g m at (%.4g, %.4g, %.4g) m, rpy (%.4g, %.4g, %.4g) deg, material %s\n",
              surf.size_m.x(), surf.size_m.y(), surf.pose.position_m.x(), surf.pose.position_m.y(),
              surf.pose.position_m.z(), surf.pose.rpy_deg.x(), surf.pose.rpy_deg.y(), surf.pose.rpy_deg.z(),
              surf.material.name.c_str());
  if (surf.texture.kind == scene::TextureSource::Kind::Generator) {
    std::printf("texture:         generator %s, seed %llu (built in %.0f ms)\n", surf.texture.generator.kind.c_str(),
                (unsigned long long)surf.texture.generator.seed, build_ms);
  } else {
    std::printf("texture:         file %s (loaded in %.0f ms)\n", surf.texture.file.c_str(), build_ms);
  }
  const std::uint64_t fingerprint = surf.mesh ? printMesh(s, built.fingerprint) : built.fingerprint;
  std::printf("sampling:        %s, %s; smoothing sigma %.3g texels\n",
              surf.sampling.filter == tex::Filter::Bilinear ? "bilinear" : "nearest",
              surf.sampling.address == tex::Address::Wrap ? "wrap" : "clamp", surf.smoothing_sigma_texels);
  const tex::TextureStats stats = tex::computeStats(map);
  std::printf("%s", tex::formatStats(stats).c_str());
  std::printf("memory:          %.2f MiB of texels\n", double(map.bytes()) / (1024.0 * 1024.0));
  if (surf.mesh)
    std::printf("fingerprint:     %s (hello_t.texture_fingerprint: the texture's %s with the mesh; docs/scenes.md)\n",
                tex::formatFingerprint(fingerprint).c_str(), tex::formatFingerprint(built.fingerprint).c_str());
  else
    std::printf("fingerprint:     %s (hello_t.texture_fingerprint; docs/scenes.md)\n",
                tex::formatFingerprint(built.fingerprint).c_str());
  if (scene::deviceCount(s) > 1) std::printf("devices:         %zu (`devices:`)\n", scene::deviceCount(s));
  for (std::size_t i = 0; i < scene::deviceCount(s); ++i) {
    const scene::Device& d = scene::deviceAt(s, i);
    if (scene::deviceCount(s) > 1) std::printf("%s:\n", d.name.c_str());
    std::printf("device:          %s %s: peak %.3g N, continuous %.3g N; stiffness %.3g N/m (%.2f of max), damping %.3g N*s/m\n",
                scene::toString(d.type), d.model.name.c_str(), d.model.peak_force_n, d.model.continuous_force_n,
                d.stiffnessNPerM(), d.stiffness_fraction, d.damping_ns_per_m);
    if (d.type == scene::DeviceType::Vrpn) {
      std::printf("address:         %s\n", d.address.c_str());
    } else {
      std::printf("script:          %zu step(s), %.2f s\n", d.script.size(), scriptDuration(d));
    }
  }
  const scene::Device& dev = s.device;
  std::printf("sound:           slab %.4g m thick, held %s; roughness beta %.3g, amplitude %.3g, spacing %.3g m;"
              " pen %.4g x r %.4g m, %s, tilt %.3g deg%s\n",
              surf.thickness_m, scene::toString(surf.held), surf.roughness.beta, surf.roughness.amplitude,
              surf.roughness.spacing_m, dev.pen.length_m, dev.pen.radius_m, dev.pen.material.name.c_str(), dev.pen.tilt_deg,
              s.audio.mute ? "; muted (audio.mute: the audio client plays silence)" : "");
  for (const scene::Material& m : s.custom_materials)
    std::printf("material:        %s (the scene's): rho %.4g kg/m^3, E %.4g Pa, nu %.3g, alpha %.3g 1/s, beta %.3g s\n",
                m.name.c_str(), m.density_kg_per_m3, m.youngs_modulus_pa, m.poisson_ratio, m.rayleigh_alpha_per_s,
                m.rayleigh_beta_s);
  std::printf("objects:         %zu\n", s.objects.size());
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    const scene::SceneObject& o = s.objects[i];
    std::printf("  %-12s %s, %.4g kg, %s", o.name.c_str(), scene::toString(o.shape), o.mass_kg,
                o.material.name.c_str());
    if (o.texture) {
      // Built here so that a texture that cannot be built is reported now, not by a client.
      const tex::TextureMap faces = scene::buildObjectTexture(s, i);
      std::printf("; faces textured: %s %dx%d relief, %.4g mm deep, %.4g m a tile",
                  o.texture->source.kind == scene::TextureSource::Kind::File ? o.texture->source.file.c_str()
                                                                              : o.texture->source.generator.kind.c_str(),
                  faces.width(), faces.height(), 1e3 * faces.maxDepth(), o.texture->tile_m);
    }
    std::printf("\n");
  }
  std::printf("rates:           servo %d Hz, physics %d Hz, visual %d Hz, audio %d Hz (fed at %d Hz)\n",
              s.rates.servo_hz, s.rates.physics_hz, s.rates.visual_hz, s.rates.audio_hz, s.rates.audio_feed_hz);
}

// Each file loaded and summarised (or only checked); its error printed as "error: ..." and the
// next file read. Returns 1 if any had an error.
int reportScenes(const std::vector<std::string>& files, bool check_only, const std::string& texture_out) {
  int status = 0;
  for (const std::string& file : files) {
    try {
      const scene::Scene s = scene::loadScene(file);
      for (const std::string& w : s.warnings) std::printf("warning: %s\n", w.c_str());
      if (check_only) {
        std::printf("%s: ok: '%s', %zu warning(s)\n", file.c_str(), s.name.c_str(), s.warnings.size());
        continue;
      }
      scene::SurfaceTextureOptions options;
      options.smooth = tex::smoothTexture;
      tex::LoadReport report;
      options.report = &report;
      const auto t0 = std::chrono::steady_clock::now();
      const scene::SceneSurface built = scene::buildSceneSurface(s, options);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      for (const std::string& w : report.warnings) std::printf("warning: %s\n", w.c_str());
      printSummary(s, built, ms);
      if (!texture_out.empty()) {
        tex::saveTexture(texture_out, *built.map);
        std::printf("wrote %s\n", texture_out.c_str());
      }
    } catch (const scene::SceneError& e) {
      std::printf("error: %s\n", e.what());
      status = 1;
    } catch (const tex::TextureError& e) {
      std::printf("error: %s\n", e.what());
      status = 1;
    }
  }
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  return thx::runProgram("scene-info", kHelp, argc, argv, [](const std::vector<std::string>& args) {
    bool check_only = false;
    std::string texture_out;
    std::vector<std::string> files;
    for (std::size_t i = 0; i < args.size(); ++i) {
      const std::string& a = args[i];
      if (a == "--check") {
        check_only = true;
      } else if (a == "--texture-out") {
        if (i + 1 >= args.size()) throw UsageError("--texture-out needs a file name");
        texture_out = args[++i];
      } else if (a.rfind("--", 0) == 0) {
        throw UsageError("unknown option '" + a + "'");
      } else {
        files.push_back(a);
      }
    }
    if (files.empty()) throw UsageError("expected at least one SCENE.yaml");
    if (!texture_out.empty() && files.size() != 1)
      throw UsageError("--texture-out writes the texture of one scene, got " + std::to_string(files.size()));
    return reportScenes(files, check_only, texture_out);
  });
}
