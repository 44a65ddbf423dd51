#include "scenes/scene_mesh.hpp"

#include "base/fnv1a64.hpp"

#include "meshes/builtin_shapes.hpp"
#include "meshes/mesh_check.hpp"
#include "meshes/mesh_import_on_demand.hpp"
#include "scenes/scene_frames.hpp"

namespace thx::scene {

namespace {

mesh::UvProjection toImport(MeshProjection p) {
  switch (p) {
    case MeshProjection::Planar: return mesh::UvProjection::Planar;
    case MeshProjection::Cylindrical: return mesh::UvProjection::Cylindrical;
    case MeshProjection::Spherical: return mesh::UvProjection::Spherical;
    case MeshProjection::None: break;
  }
  return mesh::UvProjection::None;
}

}  // namespace

SceneMesh buildSceneMesh(const Scene& scene) {
  if (!scene.surface.mesh) throw SceneError({scene.source, 0, 0}, "surface.mesh", "the scene's surface is a plane");
  const MeshSource& source = *scene.surface.mesh;
  mesh::MeshLimits limits;
  limits.max_triangles = source.max_triangles;
  limits.require_closed = source.closed;
  SceneMesh out;
  out.mesh_to_world = toIsometry(scene.surface.pose) * toIsometry(source.pose);
  try {
    if (source.kind == MeshSource::Kind::Generator) {
      mesh::GeneratedMesh shape =
          mesh::builtInShape(source.generator, source.size_m, scene.surface.size_m.x(), source.segments);
      mesh::checkMesh(shape.mesh, limits);
      out.mesh = std::move(shape.mesh);
      out.tile_m = shape.tile_used_m;
    } else {
      mesh::ImportOptions options;
      options.unit_m = source.unit_m;
      options.projection = toImport(source.projection);
      options.tile_m = scene.surface.size_m.x();
      options.limits = limits;
      out.mesh = mesh::importMeshOnDemand(source.file, options);
      out.tile_m = scene.surface.size_m;
    }
  } catch (const SceneError&) {
    throw;
  } catch (const thx::Error& e) {
    throw SceneError(source.where, "surface.mesh", e.what());
  }
  return out;
}

std::uint64_t meshSceneFingerprint(std::uint64_t texture_fingerprint, const mesh::TexturedMesh& mesh,
                                   const Eigen::Isometry3d& mesh_to_world, const Eigen::Vector2d& tile_m) {
  Fnv1a64 h;
  h.tag("thx.mesh.v1");
  h.le(texture_fingerprint);
  h.i32(std::int32_t(mesh.positions.size()));
  h.i32(std::int32_t(mesh.triangles.size()));
  for (std::size_t k = 0; k < mesh.positions.size(); ++k) {
    for (int c = 0; c < 3; ++c) h.quantised(mesh.positions[k][c]);
    for (int c = 0; c < 2; ++c) h.quantised(k < mesh.uvs.size() ? mesh.uvs[k][c] : 0.0);
  }
  for (const mesh::Triangle& t : mesh.triangles)
    for (std::uint32_t v : t) h.i32(std::int32_t(v));
  const Eigen::Matrix3d r = mesh_to_world.linear();
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) h.quantised(r(row, col));
  for (int k = 0; k < 3; ++k) h.quantised(mesh_to_world.translation()(k));
  h.quantised(tile_m.x());
  h.quantised(tile_m.y());
  return h.value();
}

}  // namespace thx::scene
