#pragma once
// The scene's TextureMap as a GL texture: RGBA32F, the decoded tangent normal in xyz and the depth
// in metres in w, texel (i, j) at texelFetch coordinate (i, j) (row 0 = the image's top). Float,
// so the shader's own bilinear filter reproduces the library's sampler to well under one LSB.
// Beside it, the depth alone (R32F) filtered by the sampler as the scene samples (bilinear or
// nearest, wrap or clamp): the relief search's one fetch per sample.
#include "clients/visual/gl_api.hpp"
#include "clients/visual/max_mipmap.hpp"
#include "textures/sampling.hpp"
#include "textures/texture_map.hpp"

namespace thx::visual {

class SurfaceTexture {
 public:
  SurfaceTexture(const tex::TextureMap& map, const tex::SampleOptions& sampling);
  ~SurfaceTexture();
  SurfaceTexture(const SurfaceTexture&) = delete;
  SurfaceTexture& operator=(const SurfaceTexture&) = delete;
  void bind(GLenum texels_unit, GLenum depths_unit) const;

 private:
  GLuint texture_ = 0, depths_ = 0;
};

// The max-mipmap (max_mipmap.hpp) as one RGBA32F texture with its levels as GL mip levels, read
// with texelFetch(level) by the accelerated relief search.
class MaxMipmapTexture {
 public:
  explicit MaxMipmapTexture(const MaxMipmap& mipmap);
  ~MaxMipmapTexture();
  MaxMipmapTexture(const MaxMipmapTexture&) = delete;
  MaxMipmapTexture& operator=(const MaxMipmapTexture&) = delete;
  void bind(GLenum unit) const;

 private:
  GLuint texture_ = 0;
};

}  // namespace thx::visual
