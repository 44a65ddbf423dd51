#include "clients/visual/textured_object_renderer.hpp"

#include "clients/visual/gl_error.hpp"
#include "meshes/textured_ball_mesh.hpp"
#include "meshes/textured_box_mesh.hpp"
#include "scenes/surface_texture.hpp"

namespace thx::visual {

struct TexturedObjectRenderer::Textured {
  tex::TextureMap map;
  mesh::TexturedMesh mesh;  // the box's or the ball's layout
  std::unique_ptr<MeshSurfaceRenderer> renderer;
};

RenderSettings texturedObjectSettings(const RenderSettings& settings) {
  RenderSettings s = settings;
  if (s.mode == SurfaceMode::Mesh) s.mode = SurfaceMode::Relief;
  s.steps.search = ReliefSearch::Linear;
  return s;
}

std::vector<ObjectInstance> untexturedObjects(const std::vector<ObjectInstance>& objects) {
  std::vector<ObjectInstance> out;
  for (const ObjectInstance& o : objects)
    if (o.textured_object < 0) out.push_back(o);
  return out;
}

TexturedObjectRenderer::TexturedObjectRenderer(const scene::Scene& scene, const RenderSettings& settings) {
  const RenderSettings object_settings = texturedObjectSettings(settings);
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const scene::SceneObject& o = scene.objects[i];
    if (!o.texture || (o.shape != scene::Shape::Box && o.shape != scene::Shape::Sphere)) {
      objects_.push_back(nullptr);
      continue;
    }
    mesh::TexturedMesh laid = o.shape == scene::Shape::Box ? mesh::texturedBoxMesh(o.size_m, o.texture->tile_m)
                                                           : mesh::texturedBallMesh(o.radius_m, o.texture->tile_m);
    auto t = std::make_unique<Textured>(Textured{scene::buildObjectTexture(scene, i), std::move(laid), nullptr});
    MeshSurface surface;
    surface.mesh = &t->mesh;
    surface.tile_m = Eigen::Vector2d::Constant(o.texture->tile_m);
    surface.map = &t->map;
    surface.use_relief = true;
    t->renderer = std::make_unique<MeshSurfaceRenderer>(surface, object_settings);
    objects_.push_back(std::move(t));
  }
  while (!objects_.empty() && !objects_.back()) objects_.pop_back();
}

TexturedObjectRenderer::~TexturedObjectRenderer() = default;

void TexturedObjectRenderer::draw(const std::vector<ObjectInstance>& objects, const Camera& camera,
                                  const Eigen::Vector3d& light_world) const {
  for (const ObjectInstance& o : objects) {
    if (o.textured_object < 0 || std::size_t(o.textured_object) >= objects_.size()) continue;
    const Textured* t = objects_[std::size_t(o.textured_object)].get();
    if (!t) continue;
    t->renderer->draw(camera, o.pose, o.pose.linear().transpose() * light_world);
  }
  checkGl("TexturedObjectRenderer::draw");
}

}  // namespace thx::visual
