#include "scenes/surface_texture.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "scenes/yaml_field.hpp"
#include "textures/generators.hpp"
#include "textures/height_from_normals.hpp"
#include "textures/texture_error.hpp"

namespace thx::scene {

namespace {

// Generators always return relief maps; a normal-map surface keeps only their normals.
tex::TextureMap withoutDepth(const tex::TextureMap& relief) {
  tex::TextureMap map(relief.width(), relief.height(), tex::Representation::Normal);
  for (int j = 0; j < relief.height(); ++j)
    for (int i = 0; i < relief.width(); ++i) map.setNormal(i, j, relief.normal(i, j));
  map.meta() = relief.meta();
  return map;
}

// Depth is stored as a fraction of maxDepth(), so copying the fractions rescales every depth.
// The normals stay those of the generator's own depth; docs/scenes.md says to prefer the
// generator's depth parameter for that reason.
tex::TextureMap withMaxDepth(const tex::TextureMap& relief, double max_depth_m) {
  tex::TextureMap map(relief.width(), relief.height(), tex::Representation::Relief, max_depth_m);
  for (int j = 0; j < relief.height(); ++j)
    for (int i = 0; i < relief.width(); ++i) {
      map.setNormal(i, j, relief.normal(i, j));
      map.setDepthCode(i, j, relief.depthCode(i, j));
    }
  map.meta() = relief.meta();
  return map;
}

tex::TextureMap generateSurface(const Surface& surface) {
  tex::TextureMap map = tex::generate(surface.texture.generator);
  if (surface.representation == tex::Representation::Normal) return withoutDepth(map);
  if (surface.max_depth_m && *surface.max_depth_m != map.maxDepth()) return withMaxDepth(map, *surface.max_depth_m);
  return map;
}

tex::TextureMap loadSurface(const Surface& surface, const SurfaceTextureOptions& options) {
  tex::LoadOptions load;
  load.green = surface.green;
  load.bad_texels = options.bad_texels;
  load.representation = surface.representation;
  if (surface.representation != tex::Representation::Normal) load.max_depth_m = surface.max_depth_m;
  tex::TextureMap map = tex::loadTexture(surface.texture.file, load, options.report);
  const tex::TextureMeta& meta = map.meta();
  const bool extent_known = meta.extent_x_m > 0.0 && meta.extent_y_m > 0.0;
  const auto differs = [](double a, double b) { return std::fabs(a - b) > 1e-6 * std::fabs(b); };
  if (options.report && extent_known &&
      (differs(meta.extent_x_m, surface.size_m.x()) || differs(meta.extent_y_m, surface.size_m.y())))
    options.report->warnings.push_back(
        surface.texture.file + ": normals were computed for " + formatNumber(meta.extent_x_m) + " x " +
        formatNumber(meta.extent_y_m) + " m but surface.size is " + formatNumber(surface.size_m.x()) + " x " +
        formatNumber(surface.size_m.y()) + " m: slopes will not match the relief's scale");
  return map;
}

}  // namespace

tex::TextureMap buildSurfaceTexture(const Scene& scene, const SurfaceTextureOptions& options) {
  const Surface& surface = scene.surface;
  const SourceLocation& where = surface.texture.where;
  try {
    tex::TextureMap map = surface.texture.kind == TextureSource::Kind::Generator ? generateSurface(surface)
                                                                                 : loadSurface(surface, options);
    if (surface.smoothing_sigma_texels > 0.0) {
      tex::SmoothOptions smooth;
      smooth.sigma_texels = surface.smoothing_sigma_texels;
      smooth.address = surface.sampling.address;
      map = options.smooth ? options.smooth(map, smooth) : tex::smoothTexture(map, smooth);
    }
    return map;
  } catch (const tex::TextureError& e) {
    throw SceneError(where, "surface.texture", e.what());
  }
}

tex::TextureMap buildObjectTexture(const Scene& scene, std::size_t index, const SurfaceTextureOptions& options) {
  const SceneObject& object = scene.objects.at(index);
  const ObjectTexture& texture = object.texture.value();
  const TextureSource& source = texture.source;
  const std::string named = "object '" + object.name + "'";
  try {
    if (source.kind == TextureSource::Kind::Generator) return tex::generate(source.generator);
    tex::LoadOptions load;
    load.bad_texels = options.bad_texels;
    tex::TextureMap map = tex::loadTexture(source.file, load, options.report);
    if (map.isRelief()) return map;
    // Normals only: the object meets the relief they integrate to, made for the tile (the same
    // reading a mesh's normal map gets; an object's contacts need depth).
    const tex::ReliefOfNormals relief = tex::reliefFromNormals(map, Eigen::Vector2d(texture.tile_m, texture.tile_m),
                                                               tex::Address::Wrap, named + "'s texture");
    const double lean = relief.mean_slope.norm();
    if (lean > tex::kLevelMeanSlope && options.report) {
      char text[400];
      std::snprintf(text, sizeof text,
                    "%s: its normal map leans on average (mean slope %.4f, %.2f degrees); the object meets the "
                    "relief its normals integrate to, which cannot lean, so that lean is lost (a map level "
                    "on average, mean slope within %.0e, loses nothing)",
                    named.c_str(), lean, std::atan(lean) * 180.0 / std::numbers::pi, tex::kLevelMeanSlope);
      options.report->warnings.emplace_back(text);
    }
    return relief.relief;
  } catch (const tex::TextureError& e) {
    throw SceneError(source.where, "objects[" + std::to_string(index) + "].texture",
                     named + ": " + e.what() + " (an object's texture is a relief map, RGBA with the depth in alpha, or a "
                     "normal map, read as the relief its normals integrate to)");
  }
}

}  // namespace thx::scene
