#pragma once
// The scene's TextureMap as a GL texture: RGBA32F, the decoded tangent normal in xyz and the depth
// in metres in w, texel (i, j) at texelFetch coordinate (i, j) (row 0 = the image's top). Float,
// so the shader's own bilinear filter reproduces the library's sampler to well under one LSB.
#include "clients/visual/gl_api.hpp"
#include "textures/texture_map.hpp"

namespace thx::visual {

class SurfaceTexture {
 public:
  explicit SurfaceTexture(const tex::TextureMap& map);
  ~SurfaceTexture();
  SurfaceTexture(const SurfaceTexture&) = delete;
  SurfaceTexture& operator=(const SurfaceTexture&) = delete;
  void bind(GLenum unit) const;

 private:
  GLuint texture_ = 0;
};

}  // namespace thx::visual
