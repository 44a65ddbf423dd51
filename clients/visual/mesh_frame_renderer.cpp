#include "clients/visual/mesh_frame_renderer.hpp"

#include "clients/visual/gl_error.hpp"

namespace thx::visual {

MeshFrameRenderer::MeshFrameRenderer(const MeshSurface& surface, const RenderSettings& settings, int width,
                                     int height)
    : settings_(settings),
      framebuffer_(width, height, settings.hit_buffer),
      surface_renderer_(surface, settings),
      mesh_to_world_rotation_(surface.mesh_to_world.linear()) {}

void MeshFrameRenderer::render(const Camera& camera, const std::vector<ObjectInstance>& objects) {
  framebuffer_.bind();
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  // FrameRenderer's background and "no hit" marks.
  glClearColor(0.08f, 0.09f, 0.11f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (settings_.hit_buffer) {
    const float none[4] = {-1.0f, -1.0f, -1.0f, 0.0f};
    glClearBufferfv(GL_COLOR, 1, none);
  }
  if (!objects.empty()) {
    const Eigen::Vector3d light_world = mesh_to_world_rotation_ * lightDirectionLocal(settings_.light);
    const bool textured = textured_objects_ && !textured_objects_->empty();
    if (textured) textured_objects_->draw(objects, camera, light_world);
    glEnable(GL_CULL_FACE);
    object_renderer_.draw(textured ? untexturedObjects(objects) : objects, camera, light_world, settings_.light);
    glDisable(GL_CULL_FACE);
  }
  surface_renderer_.draw(camera);
  glFinish();
  checkGl("MeshFrameRenderer::render");
}

}  // namespace thx::visual
