#pragma once
// One fuzzing step for scene files: yaml-cpp, then the field parsers (scenes/scene_loader.hpp),
// then, for a small texture, the surface texture the scene describes. Shared by the libFuzzer
// target and the short run in test_fuzz_scene.cpp. The input is the YAML text.
//
// The scene's folder is a fixed temporary one holding an 8x8 relief map `tex.png`, an 8x8 normal
// map `normal.png` and a path file `path.csv`, so `file:` and `path_file:` can name something
// that exists. Properties:
//  1. a refused scene raises SceneError whose location and message name the file;
//  2. an accepted scene holds the loader's promises: version 1, a name, finite numbers where the
//     format asks for them, positive rates, every warning naming the file, an existing texture
//     file or a known generator of a size within the texture limits; parsing it again gives the
//     same scene summary and warnings;
//  3. a generated texture of at most kFuzzBuildSide texels per side (larger ones are skipped: each
//     run must stay fast) or one of the two files is built: a SceneError naming the file, or a
//     map of the requested size and representation.
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>

#include "scenes/scene_loader.hpp"
#include "scenes/surface_texture.hpp"
#include "tests/fuzz/failure.hpp"
#include "textures/generators.hpp"
#include "textures/texture_io.hpp"

namespace thx::fuzz {

inline constexpr const char* kSceneSource = "fuzz.yaml";
inline constexpr int kFuzzBuildSide = 64;

namespace scene_detail {

inline void removeSceneDir();

inline const std::filesystem::path& sceneDir() {
  static const std::filesystem::path dir = [] {
    const auto d = std::filesystem::temp_directory_path() / ("thx_fuzz_scene_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    tex::TextureMap relief(8, 8, tex::Representation::Relief, 0.001);
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) relief.setDepthCode(i, j, std::uint16_t((i * 8 + j) * 1000));
    tex::saveTexture((d / "tex.png").string(), relief);
    tex::saveTexture((d / "normal.png").string(), tex::TextureMap(8, 8, tex::Representation::Normal));
    std::ofstream(d / "path.csv") << "t_s,x_m,y_m,force_n\n0,0,0,0.5\n1,0.01,0,0.5\n";
    return d;
  }();
  // Registered after `dir` exists, so it runs before `dir` is destroyed.
  static const bool removed_at_exit = std::atexit(removeSceneDir) == 0;
  (void)removed_at_exit;
  return dir;
}

// At exit, so that every test process does not leave its fixture behind.
inline void removeSceneDir() {
  std::error_code ec;
  std::filesystem::remove_all(sceneDir(), ec);
}

inline bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

inline Failure checkScene(const scene::Scene& s) {
  if (s.version != 1 || s.name.empty()) return std::string("accepted a scene without version 1 and a name");
  const scene::Surface& f = s.surface;
  if (!f.size_m.allFinite() || f.size_m.minCoeff() <= 0.0) return std::string("accepted a surface size <= 0");
  if (!finite(f.pose.position_m) || !finite(f.pose.rpy_deg)) return std::string("accepted a non-finite surface pose");
  if (f.max_depth_m && !(std::isfinite(*f.max_depth_m) && *f.max_depth_m > 0.0))
    return std::string("accepted a maximum depth that is not finite and > 0");
  if (!(std::isfinite(f.smoothing_sigma_texels) && f.smoothing_sigma_texels >= 0.0) ||
      !(std::isfinite(f.thickness_m) && f.thickness_m > 0.0))
    return std::string("accepted a bad smoothing sigma or slab thickness");
  if (f.texture.kind == scene::TextureSource::Kind::File) {
    if (!std::filesystem::is_regular_file(f.texture.file)) return "accepted a missing texture file " + f.texture.file;
  } else {
    const tex::GenerateRequest& g = f.texture.generator;
    if (!tex::findGenerator(g.kind)) return "accepted the unknown generator " + g.kind;
    if (g.size < tex::kMinTextureSide || g.size > tex::kMaxTextureSide) return std::string("accepted a texture size out of range");
    if (!g.params.count("extent")) return std::string("a generator without its extent");
    for (const auto& [name, value] : g.params)
      if (!std::isfinite(value)) return "accepted a non-finite generator parameter " + name;
  }
  for (const scene::SceneObject& o : s.objects) {
    if (!std::isfinite(o.radius_m) || !std::isfinite(o.length_m) || !finite(o.size_m) || !std::isfinite(o.mass_kg) ||
        !finite(o.pose.position_m) || !finite(o.pose.rpy_deg) || !finite(o.velocity_m_per_s) ||
        !finite(o.angular_velocity_rad_per_s))
      return "accepted a non-finite value in object '" + o.name + "'";
    if (o.mass_kg < 0.0 || (o.fixed && o.mass_kg != 0.0)) return "accepted a bad mass in object '" + o.name + "'";
  }
  const scene::Rates& r = s.rates;
  if (r.servo_hz <= 0 || r.physics_hz <= 0 || r.visual_hz <= 0 || r.audio_hz <= 0 || r.audio_feed_hz <= 0)
    return std::string("accepted a rate <= 0");
  const scene::Device& d = s.device;
  if (!std::isfinite(d.stiffness_fraction) || !std::isfinite(d.damping_ns_per_m) || !std::isfinite(d.pen.radius_m) ||
      !std::isfinite(d.pen.length_m) || !std::isfinite(d.pen.tilt_deg))
    return std::string("accepted a non-finite device value");
  for (const std::string& w : s.warnings)
    if (Failure fail = mustName(w, kSceneSource, "scene warning")) return fail;
  return std::nullopt;
}

inline std::string summary(const scene::Scene& s) {
  std::string out = s.name + "|" + std::to_string(s.objects.size()) + "|" + std::to_string(s.device.script.size());
  for (const std::string& w : s.warnings) out += "|" + w;
  return out;
}

inline Failure checkSurfaceTexture(const scene::Scene& s) {
  const scene::Surface& f = s.surface;
  int side = 8;
  if (f.texture.kind == scene::TextureSource::Kind::Generator) {
    side = f.texture.generator.size;
    if (side > kFuzzBuildSide) return std::nullopt;
  } else if (std::filesystem::path(f.texture.file).parent_path() != sceneDir()) {
    return std::nullopt;  // a file outside the fixture (the scene may name any regular file)
  }
  tex::TextureMap map;
  try {
    map = scene::buildSurfaceTexture(s);
  } catch (const scene::SceneError& e) {
    return mustName(e.what(), kSceneSource, "surface texture refusal");
  }
  if (map.width() != side || map.height() != side) return std::string("surface texture of another size");
  if (f.representation && map.representation() != *f.representation)
    return std::string("surface texture of another representation");
  if (map.isRelief() && f.max_depth_m && map.maxDepth() != *f.max_depth_m)
    return std::string("surface texture ignores the scene's maximum depth");
  return std::nullopt;
}

}  // namespace scene_detail

inline Failure fuzzSceneOnce(std::span<const std::uint8_t> data) {
  const std::string text(data.begin(), data.end());
  const std::string dir = scene_detail::sceneDir().string();
  scene::Scene s;
  try {
    s = scene::parseScene(text, kSceneSource, dir);
  } catch (const scene::SceneError& e) {
    if (e.where().file != kSceneSource) return "SceneError located in '" + e.where().file + "'";
    if (e.where().line < 0 || e.where().column < 0) return std::string("SceneError at a negative line or column");
    return mustName(e.what(), kSceneSource, "scene refusal");
  }
  if (Failure f = scene_detail::checkScene(s)) return f;
  if (scene_detail::summary(scene::parseScene(text, kSceneSource, dir)) != scene_detail::summary(s))
    return std::string("parsing the same text twice gave different scenes");
  return scene_detail::checkSurfaceTexture(s);
}

}  // namespace thx::fuzz
