#include "clients/visual/mesh_surface_renderer.hpp"

#include "base/error.hpp"
#include "clients/visual/gl_error.hpp"
#include "clients/visual/shader_sources.hpp"
#include "clients/visual/shading_uniforms.hpp"

namespace thx::visual {

MeshSurfaceRenderer::MeshSurfaceRenderer(const MeshSurface& surface, const RenderSettings& settings)
    : surface_(surface), settings_(settings) {
  checkMeshSurface(surface);
  if (settings.mode == SurfaceMode::Mesh)
    throw Error(Error::Kind::Config, "textured mesh " + surface.mesh->source +
                                         ": mode mesh:N displaces the plane's grid; a textured mesh is drawn in "
                                         "normal or relief mode");
  if (settings.mode == SurfaceMode::Relief && settings.steps.search == ReliefSearch::MaxMip)
    throw Error(Error::Kind::Config, "textured mesh " + surface.mesh->source +
                                         ": relief search maxmip walks the plane's max-mipmap; a textured mesh "
                                         "uses the linear search");
  std::vector<std::string> defines;
  if (settings.mode == SurfaceMode::Relief) defines.push_back("MODE_RELIEF");
  program_ = std::make_unique<ShaderProgram>(embeddedShader("mesh_surface.vert"),
                                             withDefines(embeddedShader("mesh_surface.frag"), defines));
  texture_ = std::make_unique<SurfaceTexture>(*surface.map, surface.sampling());
  mesh_ = std::make_unique<GpuTexturedMesh>(*surface.mesh);
}

void MeshSurfaceRenderer::draw(const Camera& camera) const {
  draw(camera, surface_.mesh_to_world, lightDirectionLocal(settings_.light));
}

void MeshSurfaceRenderer::draw(const Camera& camera, const Eigen::Isometry3d& mesh_to_world,
                               const Eigen::Vector3d& light_direction_mesh) const {
  const tex::TextureMap& map = *surface_.map;
  const Eigen::Isometry3d world_to_mesh = mesh_to_world.inverse();
  const Eigen::Matrix4f mesh_to_clip = (camera.viewProjection() * mesh_to_world.matrix()).cast<float>();
  const Eigen::Vector3f eye_mesh = (world_to_mesh * camera.eyeWorld()).cast<float>();
  const Eigen::Vector3f light_mesh = light_direction_mesh.cast<float>();
  const Eigen::Vector2f tile = surface_.tile_m.cast<float>();

  program_->use();
  texture_->bind(GL_TEXTURE0, GL_TEXTURE1);
  const ShaderProgram& p = *program_;
  glUniform2fv(p.uniform("u_tile"), 1, tile.data());
  glUniform1i(p.uniform("u_bilinear"), surface_.filter == tex::Filter::Bilinear);
  glUniformMatrix4fv(p.uniform("u_mesh_to_clip"), 1, GL_FALSE, mesh_to_clip.data());
  glUniform3fv(p.uniform("u_camera_mesh"), 1, eye_mesh.data());
  glUniform3fv(p.uniform("u_light_mesh"), 1, light_mesh.data());
  setShadingUniforms(p, settings_, map, surface_.usesRelief());
  // Closed meshes hide their back faces, and an open one (a tube) shows its inside as the
  // background: the CPU reference casts against front faces only.
  glEnable(GL_CULL_FACE);
  mesh_->draw();
  checkGl("MeshSurfaceRenderer::draw");
}

}  // namespace thx::visual
