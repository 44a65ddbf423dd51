#pragma once
// The scene's textured surface, built one way for every program that feels, simulates, hears or
// shows it (hapticd, physics-client, the benchmarks, scene-info, every new client): the texture
// as the scene describes it (buildSurfaceTexture), placed on the scene's plane with the scene's
// sampling, relief read as relief, and its fingerprint (textures/texture_fingerprint.hpp).
// hapticd announces sceneName() and the fingerprint in hello_t; a client compares them with its
// own (thx_client/scene_check.hpp). docs/scenes.md#the-scene-surface.
#include <cstdint>
#include <memory>
#include <string>

#include "scenes/scene.hpp"
#include "scenes/surface_texture.hpp"
#include "textures/textured_surface.hpp"

namespace thx::scene {

// The scene's name on the wire (hello_t.scene_name): the stem of the file it was loaded from,
// "scenes/marble_bricks.yaml" -> "marble_bricks". A client on another host finds the scene as
// NAME.yaml in its own scenes folder (thx_client/scene_check.hpp). Not the `name:` field, which
// is free text for people ("bricks and a marble").
std::string sceneName(const Scene& scene);

struct SceneSurface {
  std::string scene_name;                    // sceneName(scene)
  std::unique_ptr<const tex::TextureMap> map;  // owned here; `surface` points at it (moves keep it valid)
  // The map's slope steps, owned here and set on `surface`: the servo's renderers skip reading a
  // texel's neighbours where these show no crease can be there (server/proxy_renderer.hpp).
  std::unique_ptr<const tex::TexelSlopeSteps> slope_steps;
  tex::TexturedSurface surface;              // the map on the scene's plane and sampling
  std::uint64_t fingerprint = 0;             // tex::textureFingerprint(surface)
};

// Throws SceneError (located at the scene's `texture:` field) as buildSurfaceTexture does.
SceneSurface buildSceneSurface(const Scene& scene, const SurfaceTextureOptions& options = {});

// The scene's plane mapping and sampling around a map: what buildSceneSurface places its map on.
// `use_relief` false reads a relief map as a normal map (the benchmarks compare both readings);
// true reads the map as it is (a normal map stays one).
tex::TexturedSurface placeOnScenePlane(const Scene& scene, const tex::TextureMap& map, bool use_relief = true);

}  // namespace thx::scene
