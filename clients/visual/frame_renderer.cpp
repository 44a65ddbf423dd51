#include "clients/visual/frame_renderer.hpp"

#include "clients/visual/gl_error.hpp"

namespace thx::visual {

FrameRenderer::FrameRenderer(const tex::TexturedSurface& surface, const RenderSettings& settings, int width,
                             int height)
    : surface_(surface),
      settings_(settings),
      framebuffer_(width, height, settings.hit_buffer),
      surface_renderer_(surface, settings) {}

void FrameRenderer::render(const Camera& camera, const std::vector<ObjectInstance>& objects) {
  framebuffer_.bind();
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glClearColor(0.08f, 0.09f, 0.11f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (settings_.hit_buffer) {
    const float none[4] = {-1.0f, -1.0f, -1.0f, 0.0f};
    glClearBufferfv(GL_COLOR, 1, none);
  }
  const Eigen::Vector3d light_world = surface_.mapping().directionToWorld(lightDirectionLocal(settings_.light));
  if (textured_objects_ && !textured_objects_->empty()) {
    textured_objects_->draw(objects, camera, light_world);
    glEnable(GL_CULL_FACE);
    object_renderer_.draw(untexturedObjects(objects), camera, light_world, settings_.light);
  } else {
    object_renderer_.draw(objects, camera, light_world, settings_.light);
  }
  // The plane is seen from both sides in mesh mode's grazing views: no culling for it.
  glDisable(GL_CULL_FACE);
  surface_renderer_.draw(camera);
  glFinish();
  checkGl("FrameRenderer::render");
}

}  // namespace thx::visual
