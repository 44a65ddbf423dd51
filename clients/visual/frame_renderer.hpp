#pragma once
// The one render path: objects and pen first (so the rasteriser's early depth test skips the
// plane's pixels they cover), then the textured plane, into a Framebuffer. Presenters (files,
// a window) only read the framebuffer.
#include <memory>
#include <vector>

#include "clients/visual/framebuffer.hpp"
#include "clients/visual/object_renderer.hpp"
#include "clients/visual/textured_object_renderer.hpp"
#include "clients/visual/surface_renderer.hpp"

namespace thx::visual {

class FrameRenderer {
 public:
  FrameRenderer(const tex::TexturedSurface& surface, const RenderSettings& settings, int width, int height);
  // Draws and waits for the GPU (glFinish), so a following read or a timing is of this frame.
  void render(const Camera& camera, const std::vector<ObjectInstance>& objects);
  // The scene's textured objects (objects[].texture) are drawn textured from now on; without
  // this they are drawn as plain boxes. Throws scene::SceneError for a texture that fails to build.
  void setTexturedObjects(const scene::Scene& scene) {
    textured_objects_ = std::make_unique<TexturedObjectRenderer>(scene, settings_);
  }
  const Framebuffer& framebuffer() const { return framebuffer_; }
  const RenderSettings& settings() const { return settings_; }

 private:
  const tex::TexturedSurface& surface_;
  RenderSettings settings_;
  Framebuffer framebuffer_;
  SurfaceRenderer surface_renderer_;
  ObjectRenderer object_renderer_;
  std::unique_ptr<TexturedObjectRenderer> textured_objects_;
};

}  // namespace thx::visual
