#pragma once
// Shared by the textured-mesh tests (issue 28): a generated mesh with a texture, rendered alone
// with the references' lighting (visual_fixture.hpp) and compared with its CPU reference
// (clients/visual/mesh_reference.hpp) pixel by pixel.
#include <cmath>
#include <cstdio>

#include "clients/visual/mesh_frame_renderer.hpp"
#include "clients/visual/mesh_image_error.hpp"
#include "meshes/mesh_generators.hpp"
#include "tests/visual/visual_fixture.hpp"

namespace thx::visual::testing {

// A generated mesh with its texture; the MeshSurface points into both.
struct TexturedTestMesh {
  std::unique_ptr<mesh::GeneratedMesh> generated;
  std::unique_ptr<tex::TextureMap> map;
  MeshSurface surface;
};

inline TexturedTestMesh texturedMesh(mesh::GeneratedMesh generated, tex::TextureMap map, bool relief) {
  TexturedTestMesh t{std::make_unique<mesh::GeneratedMesh>(std::move(generated)),
                     std::make_unique<tex::TextureMap>(std::move(map)), {}};
  t.surface.mesh = &t.generated->mesh;
  t.surface.tile_m = t.generated->tile_used_m;
  t.surface.map = t.map.get();
  t.surface.use_relief = relief;
  return t;
}

// The camera orbits `centre` (mesh frame = world here); elevation above the mesh's xy plane.
inline Camera orbitCamera(double elevation_deg, double azimuth_deg, double distance_m, const Eigen::Vector3d& centre) {
  CameraPlacement c;
  c.elevation_deg = elevation_deg;
  c.azimuth_deg = azimuth_deg;
  c.distance_m = distance_m;
  return Camera(c, Eigen::Isometry3d(Eigen::Translation3d(centre)), kImageSide, kImageSide);
}

struct MeshFrame {
  Rgba8Image colour;
  FloatImage hits;
};

inline MeshFrame renderMesh(const MeshSurface& surface, const RenderSettings& settings, const Camera& camera) {
  context();
  MeshFrameRenderer renderer(surface, settings, kImageSide, kImageSide);
  renderer.render(camera);
  return {renderer.framebuffer().readColour(), renderer.framebuffer().readHits()};
}

// The GPU's relief depth against the reference's, over the pixels the comparison counts (the
// reference's 3x3 neighbourhood on the mesh): mean |difference| in metres.
inline double meanDepthError(const ReferenceImage& reference, const FloatImage& hits) {
  double sum = 0;
  int n = 0;
  for (int y = 1; y + 1 < reference.height; ++y)
    for (int x = 1; x + 1 < reference.width; ++x) {
      bool interior = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) interior = interior && reference.at(x + dx, y + dy).has_value();
      if (!interior || hits.at(x, y, 3) != 1.0f) continue;
      sum += std::fabs(double(hits.at(x, y, 2)) + reference.at(x, y)->p_local.z());
      ++n;
    }
  return n ? sum / n : 1e9;
}

// The binary search's last interval: the GPU's hit lies within it of the exact one.
inline double finalInterval(const tex::TextureMap& map, const ReliefSteps& steps) {
  return map.maxDepth() / (steps.linear * std::exp2(steps.binary));
}

struct MeshComparison {
  PixelStats stats;
  double mean_depth_error_m = 0;
};

// Renders and compares with the CPU reference; prints the numbers the tests pin.
inline MeshComparison meshAgainstReference(const char* what, const MeshSurface& surface, const RenderSettings& settings,
                                           const Camera& camera) {
  const MeshFrame frame = renderMesh(surface, settings, camera);
  const MeshReference reference(surface);
  const bool relief = settings.mode == SurfaceMode::Relief;
  const ReferenceLight light{lightDirectionLocal(settings.light), relief && settings.steps.shadow > 0};
  const ReferenceImage image = meshReferenceImage(reference, camera, kImageSide, kImageSide, relief, light);
  MeshComparison c{compareWithMeshReference(reference, image, frame.colour, frame.hits), meanDepthError(image, frame.hits)};
  EXPECT_EQ(c.stats.not_surface, 0) << what << ": pixels the reference sees on the mesh and the frame does not";
  std::printf("%-34s %5d px, other texel %.4f, mean %.3f LSB, max %3d LSB, depth error %.2e m\n", what,
              c.stats.compared, c.stats.otherTexelFraction(), c.stats.meanError(), c.stats.max_error,
              c.mean_depth_error_m);
  return c;
}

}  // namespace thx::visual::testing
