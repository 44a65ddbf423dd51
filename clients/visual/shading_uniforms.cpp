#include "clients/visual/shading_uniforms.hpp"

#include "clients/visual/gl_api.hpp"

namespace thx::visual {

void setShadingUniforms(const ShaderProgram& p, const RenderSettings& settings, const tex::TextureMap& map,
                        bool use_relief) {
  glUniform1i(p.uniform("u_texels"), 0);
  glUniform1i(p.uniform("u_depths"), 1);
  glUniform2i(p.uniform("u_texels_size"), map.width(), map.height());
  glUniform3fv(p.uniform("u_albedo"), 1, settings.plane_albedo.data());
  glUniform1f(p.uniform("u_ambient"), float(settings.light.ambient));
  glUniform1f(p.uniform("u_specular"), float(settings.light.specular));
  glUniform1f(p.uniform("u_max_depth"), use_relief ? float(map.maxDepth()) : 0.0f);
  glUniform1i(p.uniform("u_linear_steps"), settings.steps.linear);
  glUniform1i(p.uniform("u_binary_steps"), settings.steps.binary);
  glUniform1i(p.uniform("u_shadow_steps"), settings.steps.shadow);
}

}  // namespace thx::visual
