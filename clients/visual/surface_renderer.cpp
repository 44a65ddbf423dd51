#include "clients/visual/surface_renderer.hpp"

#include "clients/visual/gl_error.hpp"
#include "clients/visual/shader_sources.hpp"
#include "clients/visual/shading_uniforms.hpp"

namespace thx::visual {

SurfaceRenderer::SurfaceRenderer(const tex::TexturedSurface& surface, const RenderSettings& settings)
    : surface_(surface), settings_(settings) {
  std::vector<std::string> defines;
  if (settings.mode == SurfaceMode::Relief) defines.push_back("MODE_RELIEF");
  if (settings.mode == SurfaceMode::Mesh) defines.push_back("MODE_MESH");
  const bool maxmip = settings.mode == SurfaceMode::Relief && settings.steps.search == ReliefSearch::MaxMip;
  if (maxmip) defines.push_back("SEARCH_MAXMIP");
  program_ = std::make_unique<ShaderProgram>(embeddedShader("surface.vert"),
                                             withDefines(embeddedShader("surface.frag"), defines));
  texture_ = std::make_unique<SurfaceTexture>(surface.map(), surface.sampling());
  if (maxmip) {
    maxmip_ = std::make_unique<MaxMipmap>(buildMaxMipmap(surface.map(), surface.sampling()));
    maxmip_texture_ = std::make_unique<MaxMipmapTexture>(*maxmip_);
  }
  mesh_ = std::make_unique<GpuMesh>(settings.mode == SurfaceMode::Mesh ? displacedGrid(surface, settings.mesh_n)
                                                                       : planeQuad(surface.mapping().size_m));
}

void SurfaceRenderer::draw(const Camera& camera) const {
  const tex::PlaneMapping& mapping = surface_.mapping();
  const tex::TextureMap& map = surface_.map();
  const Eigen::Matrix4f plane_to_clip = (camera.viewProjection() * mapping.plane_to_world.matrix()).cast<float>();
  const Eigen::Vector3f eye_local = mapping.toLocal(camera.eyeWorld()).cast<float>();
  const Eigen::Vector3f light_local = lightDirectionLocal(settings_.light).cast<float>();
  const bool wrap = surface_.sampling().address == tex::Address::Wrap;

  program_->use();
  texture_->bind(GL_TEXTURE0, GL_TEXTURE1);
  const ShaderProgram& p = *program_;
  glUniform2f(p.uniform("u_plane_size"), float(mapping.size_m.x()), float(mapping.size_m.y()));
  glUniform1i(p.uniform("u_wrap"), wrap);
  glUniform1i(p.uniform("u_bilinear"), surface_.sampling().filter == tex::Filter::Bilinear);
  glUniform1i(p.uniform("u_flat_beyond_edge"), surface_.usesRelief() && !wrap);
  glUniformMatrix4fv(p.uniform("u_plane_to_clip"), 1, GL_FALSE, plane_to_clip.data());
  glUniform3fv(p.uniform("u_camera_local"), 1, eye_local.data());
  glUniform3fv(p.uniform("u_light_local"), 1, light_local.data());
  setShadingUniforms(p, settings_, map, surface_.usesRelief());
  if (maxmip_) {
    maxmip_texture_->bind(GL_TEXTURE2);
    glUniform1i(p.uniform("u_maxmip"), 2);
    glUniform1i(p.uniform("u_maxmip_top"), maxmip_->topLevel());
    glUniform2i(p.uniform("u_maxmip_cells"), maxmip_->cells_x, maxmip_->cells_y);
    const auto pow2 = [](int n) { return (n & (n - 1)) == 0; };
    glUniform1i(p.uniform("u_maxmip_pow2"), pow2(maxmip_->cells_x) && pow2(maxmip_->cells_y));
    glUniform1f(p.uniform("u_grid_shift"), (maxmip_->between_centres ? 0.5f : 0.0f) - float(maxmip_->offset));
  }
  mesh_->draw();
  checkGl("SurfaceRenderer::draw");
}

}  // namespace thx::visual
