#pragma once
// Builds the surface's texture exactly as the scene describes it: generated or loaded, with the
// scene's representation, maximum depth and green convention, then smoothed if asked.
#include <functional>

#include "scenes/scene.hpp"
#include "textures/smoothing.hpp"
#include "textures/texture_io.hpp"
#include "textures/texture_map.hpp"

namespace thx::scene {

struct SurfaceTextureOptions {
  tex::BadTexelPolicy bad_texels = tex::BadTexelPolicy::Reject;
  // Gaussian smoothing when smoothing_sigma > 0, called with sigma = smoothing_sigma and the
  // scene's address mode. Unset: `thx::tex::smoothTexture` (dependency-free, so hapticd smooths
  // too); a test may pass another.
  std::function<tex::TextureMap(const tex::TextureMap&, const tex::SmoothOptions&)> smooth;
  tex::LoadReport* report = nullptr;  // receives texel counts and warnings (file textures, extent)
};

// Throws SceneError (located at the scene's `texture:` field) wrapping any texture error.
tex::TextureMap buildSurfaceTexture(const Scene& scene, const SurfaceTextureOptions& options = {});

// scene.objects[index]'s texture (objects[].texture: a box's faces, a ball's bump map), always a
// relief map (it shapes contacts through its depth): a file holding only normals becomes the relief
// they integrate to over the object's tile (tex::reliefFromNormals, wrapped), and a map leaning on
// average (mean slope above tex::kLevelMeanSlope), whose lean that relief cannot hold, adds a
// warning naming the object to `options.report`. Throws SceneError located at the object's
// `texture:`, naming the object. Requires that object to have a texture.
tex::TextureMap buildObjectTexture(const Scene& scene, std::size_t index, const SurfaceTextureOptions& options = {});

}  // namespace thx::scene
