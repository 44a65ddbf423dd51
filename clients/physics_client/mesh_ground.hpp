#pragma once
// A mesh scene's surface (surface.mesh, docs/scenes.md) for the physics client: the scene's mesh
// (scenes/scene_mesh.hpp, built as hapticd builds it) as a static textured Bullet body, and where
// on the texture a contact is. The plane answers that with its mapping; a mesh with the foot of a
// body's centre on its smooth surface (the walk of clients/physics/mesh_contact.hpp), the uv there
// and the texel that uv falls in. Configuration allocates; the queries do not.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>

#include "clients/physics/mesh_contact.hpp"
#include "clients/physics/physics_world.hpp"
#include "scenes/scene.hpp"
#include "scenes/scene_mesh.hpp"
#include "textures/height_from_normals.hpp"
#include "textures/textured_surface.hpp"

namespace thx::physclient {

class MeshGround {
 public:
  // Builds the scene's mesh (throws scene::SceneError as buildSceneMesh does). `texture` is the
  // scene's surface texture (scene_surface.hpp); it and this outlive the world it is added to.
  MeshGround(const scene::Scene& scene, const tex::TexturedSurface& texture);
  MeshGround(const MeshGround&) = delete;  // its contact options point into it
  MeshGround& operator=(const MeshGround&) = delete;

  const scene::SceneMesh& sceneMesh() const { return scene_mesh_; }
  // The mesh as a static body of `world`, its contacts steered by the texture: a ball meets a
  // relief as its sphere does and is lifted onto it, and boxes, capsules and cylinders meet it on
  // its chart (docs/physics.md, "A ball on a relief, lifted", "Plain objects on a relief mesh"). A
  // normal map is met by every body as the relief its normals integrate to; where they lean on
  // average (their mean slope beyond kLevelSlope: a periodic relief cannot lean) its contacts'
  // normals lean by that slope, the heights held: a ball's lift, and the chart's points of the
  // other shapes (phys::leanChartContact; docs/physics.md, "Mesh scenes in physics-client").
  btRigidBody& addTo(phys::PhysicsWorld& world, const phys::BodyMaterial& material) const;
  // How the mesh's contacts read the texture (what addTo gives the world).
  const phys::MeshContactOptions& contactOptions() const { return options_; }

  struct Place {
    std::uint32_t triangle = 0;
    Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
    Eigen::Vector3d p_world = Eigen::Vector3d::Zero();
    tex::TexCoord uv;
    Eigen::Vector2d metres_per_uv = Eigen::Vector2d::Ones();  // the texture's scale laid here
  };
  // A normal map's mean slope below which it is taken as level (a map made from a periodic height
  // field has none but its normals' rounding).
  static constexpr double kLevelSlope = tex::kLevelMeanSlope;

  // The closest point of `triangle` to p_world (a contact point Bullet reported on it).
  Place on(std::uint32_t triangle, const Eigen::Vector3d& p_world) const;
  // The foot of c_world (a body's centre) on the smooth surface, walking from `near` (a triangle
  // the body touches), on the side of the surface c_world is on.
  Place footOf(const Eigen::Vector3d& c_world, std::uint32_t near) const;
  // The unwrapped texel the place's uv falls in (as TexturedSurface::texelContaining counts).
  void texelOf(const tex::TexCoord& uv, long long& i, long long& j) const;
  // Texel (i, j)'s own normal (nearest, not bilinear) in the world, laid on the surface at `at`.
  Eigen::Vector3d texelNormalWorld(long long i, long long j, const Place& at) const;

 private:
  Place placeAt(std::uint32_t triangle, const Eigen::Vector3d& b) const;

  const tex::TexturedSurface* texture_;
  scene::SceneMesh scene_mesh_;
  phys::ContactMesh contact_mesh_;
  // A normal map's relief, the heights its normals integrate to (textures/height_from_normals.hpp),
  // and their mean slope.
  std::optional<tex::TextureMap> relief_;
  Eigen::Vector2d mean_slope_ = Eigen::Vector2d::Zero();
  // What a ball meets: a relief map's relief, or a normal map's.
  std::optional<tex::BallOnRelief> ball_relief_;
  phys::MeshContactOptions options_;
};

}  // namespace thx::physclient
