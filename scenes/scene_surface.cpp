#include "scenes/scene_surface.hpp"

#include <filesystem>

#include "scenes/scene_frames.hpp"
#include "textures/texture_fingerprint.hpp"

namespace thx::scene {

std::string sceneName(const Scene& scene) { return std::filesystem::path(scene.source).stem().string(); }

tex::TexturedSurface placeOnScenePlane(const Scene& scene, const tex::TextureMap& map, bool use_relief) {
  return tex::TexturedSurface(map, planeMapping(scene.surface), scene.surface.sampling, use_relief && map.isRelief());
}

SceneSurface buildSceneSurface(const Scene& scene, const SurfaceTextureOptions& options) {
  SceneSurface s;
  s.scene_name = sceneName(scene);
  // buildSurfaceTexture has already dropped the depth of a relief the scene reads as a normal map.
  s.map = std::make_unique<const tex::TextureMap>(buildSurfaceTexture(scene, options));
  s.slope_steps = std::make_unique<const tex::TexelSlopeSteps>(*s.map);
  s.surface = placeOnScenePlane(scene, *s.map);
  s.surface.setSlopeSteps(s.slope_steps.get());
  s.fingerprint = tex::textureFingerprint(s.surface);
  return s;
}

}  // namespace thx::scene
