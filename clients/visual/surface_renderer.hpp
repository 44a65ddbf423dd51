#pragma once
// Draws the scene's textured plane in one mode (normal, relief, displaced mesh) from the same
// TexturedSurface every other sense uses: its map, plane mapping and sampling.
#include <memory>

#include "clients/visual/camera.hpp"
#include "clients/visual/gpu_mesh.hpp"
#include "clients/visual/render_settings.hpp"
#include "clients/visual/shader_program.hpp"
#include "clients/visual/texture_upload.hpp"
#include "textures/textured_surface.hpp"

namespace thx::visual {

class SurfaceRenderer {
 public:
  // Needs a current GL context. A surface without relief has depth 0 everywhere, so relief mode
  // then shows what normal mode shows.
  SurfaceRenderer(const tex::TexturedSurface& surface, const RenderSettings& settings);
  void draw(const Camera& camera) const;

 private:
  const tex::TexturedSurface& surface_;
  RenderSettings settings_;
  std::unique_ptr<ShaderProgram> program_;
  std::unique_ptr<SurfaceTexture> texture_;
  std::unique_ptr<MaxMipmap> maxmip_;  // relief with --search maxmip only
  std::unique_ptr<MaxMipmapTexture> maxmip_texture_;
  std::unique_ptr<GpuMesh> mesh_;
};

}  // namespace thx::visual
