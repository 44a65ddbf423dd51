#include "clients/visual/object_renderer.hpp"

#include "clients/visual/gl_error.hpp"
#include "clients/visual/glyphs.hpp"
#include "clients/visual/shader_sources.hpp"

namespace thx::visual {

ObjectRenderer::ObjectRenderer()
    : program_(std::make_unique<ShaderProgram>(embeddedShader("object.vert"), embeddedShader("object.frag"))),
      sphere_(std::make_unique<GpuMesh>(unitSphere(32, 16))),
      box_(std::make_unique<GpuMesh>(unitBox())),
      cylinder_(std::make_unique<GpuMesh>(unitCylinder(32))) {}

void ObjectRenderer::draw(const std::vector<ObjectInstance>& objects, const Camera& camera,
                          const Eigen::Vector3d& light_world, const Lighting& light) const {
  if (objects.empty()) return;
  const ShaderProgram& p = *program_;
  p.use();
  const Eigen::Matrix4f view_projection = camera.viewProjection().cast<float>();
  const Eigen::Vector3f eye = camera.eyeWorld().cast<float>(), l = light_world.cast<float>();
  glUniformMatrix4fv(p.uniform("u_view_projection"), 1, GL_FALSE, view_projection.data());
  glUniform3fv(p.uniform("u_camera_world"), 1, eye.data());
  glUniform3fv(p.uniform("u_light_world"), 1, l.data());
  glUniform1f(p.uniform("u_ambient"), float(light.ambient));
  glUniform1f(p.uniform("u_specular"), float(light.specular));
  for (const ObjectInstance& o : objects) {
    const Eigen::Matrix4f model = o.model.matrix().cast<float>();
    const Eigen::Matrix3f normal_matrix = o.model.linear().inverse().transpose().cast<float>();
    glUniformMatrix4fv(p.uniform("u_model"), 1, GL_FALSE, model.data());
    glUniformMatrix3fv(p.uniform("u_normal_matrix"), 1, GL_FALSE, normal_matrix.data());
    glUniform3fv(p.uniform("u_albedo"), 1, o.albedo.data());
    const std::optional<Glyph> glyph = o.shape == UnitShape::Box && o.letter ? glyph5x7(o.letter) : std::nullopt;
    GLint rows[7] = {0, 0, 0, 0, 0, 0, 0};
    if (glyph)
      for (int r = 0; r < 7; ++r) rows[r] = (*glyph)[std::size_t(r)];
    glUniform1i(p.uniform("u_has_glyph"), glyph.has_value());
    glUniform1iv(p.uniform("u_glyph"), 7, rows);
    switch (o.shape) {
      case UnitShape::Sphere: sphere_->draw(); break;
      case UnitShape::Box: box_->draw(); break;
      case UnitShape::Cylinder: cylinder_->draw(); break;
    }
  }
  checkGl("ObjectRenderer::draw");
}

}  // namespace thx::visual
