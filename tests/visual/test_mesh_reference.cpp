// Textured meshes (issue 28) against the CPU reference (clients/visual/mesh_reference.hpp): normal
// mapping on a sphere and a cylinder within the plane's thresholds (test_normal_reference.cpp), a
// mirrored chart (handedness -1) lit as the mirror image of an unmirrored one, a uniformly tilted
// normal map on a cylinder against the analytically tilted normal, relief on a cylinder and a
// sphere against the exact tangent-space reference (hit texel, intensity, hit depth).
#include "tests/visual/mesh_fixture.hpp"

#include <numbers>

#include "clients/visual/shader_sources.hpp"

namespace thx::visual::testing::test_mesh_reference {
namespace {

tex::TextureMap generatedMap(const std::string& kind, int texels, std::map<std::string, double> params, double extent) {
  params["extent"] = extent;
  return tex::generate({kind, texels, params, 7});
}

void expectNormalWithinOneLsb(const MeshComparison& c) {
  EXPECT_GT(c.stats.compared, kImageSide * kImageSide / 4);
  EXPECT_LE(c.stats.meanError(), 1.0);
  EXPECT_LE(c.stats.max_error, 4);
}

TEST(VisualMeshReference, MeshShadersCompileInBothModes) {
  context();
  for (const std::vector<std::string>& defines : {std::vector<std::string>{}, {"MODE_RELIEF"}})
    EXPECT_NO_THROW(
        ShaderProgram(embeddedShader("mesh_surface.vert"), withDefines(embeddedShader("mesh_surface.frag"), defines)));
}

TEST(VisualMeshReference, NormalMappedSphere) {
  // 4 cm sphere, 64 x 32 segments, bumps of 2.5 cm period on a 4 cm tile (6 x 3 tiles); seen
  // from 12 cm: the sphere fills most of the picture, its limb included.
  const TexturedTestMesh t = texturedMesh(mesh::sphere(0.04, 64, 32, 0.04),
                                          generatedMap("sine", 64, {{"amplitude", 0.0015}, {"period", 0.02}}, 0.04), false);
  const RenderSettings settings = referenceLighting(SurfaceMode::Normal);
  expectNormalWithinOneLsb(meshAgainstReference("normal sphere", t.surface, settings,
                                                orbitCamera(30, -70, 0.12, Eigen::Vector3d::Zero())));
}

TEST(VisualMeshReference, NormalMappedCylinderSeenObliquely) {
  const TexturedTestMesh t =
      texturedMesh(mesh::cylinder(0.03, 0.08, 96, 8, 0.05), generatedMap("bricks", 128, {}, 0.05), false);
  const RenderSettings settings = referenceLighting(SurfaceMode::Normal);
  expectNormalWithinOneLsb(meshAgainstReference("normal cylinder", t.surface, settings,
                                                orbitCamera(40, -60, 0.11, {0, 0, 0.04})));
}

// The texture mirrored left to right: column i -> W-1-i, the normal's x negated. A chart whose u
// runs the other way reads the original map as this one.
tex::TextureMap mirrored(const tex::TextureMap& map) {
  tex::TextureMap m(map.width(), map.height(), map.representation(), map.maxDepth());
  for (int j = 0; j < map.height(); ++j)
    for (int i = 0; i < map.width(); ++i) {
      const Eigen::Vector3f n = map.normal(map.width() - 1 - i, j);
      m.setNormal(i, j, {-n.x(), n.y(), n.z()});
      m.setDepthCode(i, j, map.depthCode(map.width() - 1 - i, j));
    }
  return m;
}

// The mesh's triangles with u running the other way; its frames rebuilt (tangents flip, and the
// bitangent stays along +v only through handedness -1).
mesh::GeneratedMesh mirroredChart(const mesh::GeneratedMesh& g) {
  mesh::GeneratedMesh m{{}, g.tile_used_m};
  m.mesh.source = g.mesh.source + ", u mirrored";
  m.mesh.positions = g.mesh.positions;
  m.mesh.triangles = g.mesh.triangles;
  for (const Eigen::Vector2d& uv : g.mesh.uvs) m.mesh.uvs.emplace_back(-uv.x(), uv.y());
  mesh::buildVertexFrames(m.mesh);
  return m;
}

int meanDifferenceTimes100(const Rgba8Image& a, const Rgba8Image& b, int& max_difference) {
  long sum = 0;
  max_difference = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const int d = std::abs(int(a.at(x, y, 0)) - int(b.at(x, y, 0)));
      sum += d;
      max_difference = std::max(max_difference, d);
    }
  return int(100 * sum / (long(a.width) * a.height));
}

TEST(VisualMeshReference, MirroredChartLightsTheBumpsAsTheirMirrorImage) {
  const mesh::GeneratedMesh plain = mesh::cylinder(0.03, 0.06, 96, 8, 0.03);
  const tex::TextureMap pebbles = generatedMap("pebbles", 64, {}, 0.03);
  // A: u as generated, the mirrored map. B: u mirrored, the original map. Both put the same
  // bumps on the same places of the surface, with the same normals.
  const TexturedTestMesh a = texturedMesh(plain, mirrored(pebbles), false);
  const TexturedTestMesh b = texturedMesh(mirroredChart(plain), pebbles, false);
  for (float h : b.generated->mesh.handedness) ASSERT_EQ(h, -1.0f);
  for (float h : a.generated->mesh.handedness) ASSERT_EQ(h, 1.0f);

  const RenderSettings settings = referenceLighting(SurfaceMode::Normal);
  const Camera camera = orbitCamera(20, -80, 0.09, {0, 0, 0.03});
  const MeshFrame fa = renderMesh(a.surface, settings, camera), fb = renderMesh(b.surface, settings, camera);
  int max_difference = 0;
  const int mean_x100 = meanDifferenceTimes100(fa.colour, fb.colour, max_difference);
  std::printf("mirrored chart: mean difference %.2f LSB, max %d LSB\n", mean_x100 / 100.0, max_difference);
  EXPECT_LE(mean_x100, 20);
  EXPECT_LE(max_difference, 3);
  expectNormalWithinOneLsb(meshAgainstReference("normal, mirrored chart", b.surface, settings, camera));

  // The same chart read with handedness +1 (the bitangent along -v): the bumps' slopes along v
  // turn over, and the picture shows it.
  TexturedTestMesh wrong = texturedMesh(mirroredChart(plain), pebbles, false);
  for (float& h : wrong.generated->mesh.handedness) h = 1.0f;
  const MeshFrame fw = renderMesh(wrong.surface, settings, camera);
  const int wrong_x100 = meanDifferenceTimes100(fa.colour, fw.colour, max_difference);
  std::printf("mirrored chart read with handedness +1: mean difference %.2f LSB\n", wrong_x100 / 100.0);
  EXPECT_GE(wrong_x100, 200);
}

// The first point of the tube x^2 + y^2 = r^2, 0 <= z <= h a ray meets from outside.
std::optional<Eigen::Vector3d> tubeHit(const Ray& ray, double r, double h) {
  const Eigen::Vector2d o = ray.origin.head<2>(), d = ray.direction.head<2>();
  const double a = d.squaredNorm(), b = 2 * o.dot(d), c = o.squaredNorm() - r * r;
  const double disc = b * b - 4 * a * c;
  if (a == 0 || disc < 0) return std::nullopt;
  const double t = (-b - std::sqrt(disc)) / (2 * a);
  const Eigen::Vector3d p = ray.origin + t * ray.direction;
  if (t <= 0 || p.z() < 0 || p.z() > h) return std::nullopt;
  return p;
}

// Every texel's normal tilted by `tilt` towards +u, drawn on a tube whose stated tile (the size the
// normals were made for) is `made_for_factor` x the tile its uv lays: the picture shades as the
// normal whose slope is tan(tilt) x made_for_factor, sin(a) * east + cos(a) * outward at every
// point (u runs east around z), as the haptic chart turns it.
void expectTiltedMapShading(double made_for_factor) {
  const double tilt = 30 * std::numbers::pi / 180, r = 0.03, h = 0.08;
  const double a = std::atan(std::tan(tilt) * made_for_factor);
  tex::TextureMap map(4, 4, tex::Representation::Normal);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) map.setNormal(i, j, {float(std::sin(tilt)), 0.0f, float(std::cos(tilt))});
  TexturedTestMesh t = texturedMesh(mesh::cylinder(r, h, 256, 4, 0.03), std::move(map), false);
  t.surface.tile_m.x() *= made_for_factor;
  const RenderSettings settings = referenceLighting(SurfaceMode::Normal);
  const Camera camera = orbitCamera(20, -70, 0.1, {0, 0, h / 2});
  const MeshFrame frame = renderMesh(t.surface, settings, camera);
  const Eigen::Vector3d l = lightDirectionLocal(settings.light);

  std::vector<std::optional<double>> expected(std::size_t(kImageSide) * kImageSide);
  for (int y = 0; y < kImageSide; ++y)
    for (int x = 0; x < kImageSide; ++x)
      if (const auto p = tubeHit(camera.pixelRay(x, y), r, h)) {
        const double phi = std::atan2(p->y(), p->x());
        const Eigen::Vector3d outward(std::cos(phi), std::sin(phi), 0), east(-std::sin(phi), std::cos(phi), 0);
        expected[std::size_t(y) * kImageSide + x] = std::max(0.0, (std::sin(a) * east + std::cos(a) * outward).dot(l));
      }
  int compared = 0, max_error = 0;
  double sum = 0;
  for (int y = 1; y + 1 < kImageSide; ++y)
    for (int x = 1; x + 1 < kImageSide; ++x) {
      bool interior = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) interior = interior && expected[std::size_t(y + dy) * kImageSide + x + dx];
      if (!interior) continue;
      const int e = std::abs(int(frame.colour.at(x, y, 0)) - int(std::lround(255 * *expected[std::size_t(y) * kImageSide + x])));
      ++compared, sum += e, max_error = std::max(max_error, e);
    }
  std::printf("tilted map on a tube, made for %.1fx the laid tile: %d px, mean %.3f LSB, max %d LSB\n", made_for_factor,
              compared, sum / compared, max_error);
  EXPECT_GT(compared, kImageSide * kImageSide / 4);
  EXPECT_LE(sum / compared, 1.0);
  EXPECT_LE(max_error, 4);
}

TEST(VisualMeshReference, UniformlyTiltedMapOnACylinderShadesAsTheTiltedNormal) { expectTiltedMapShading(1.0); }

// The map's normals made for a tile twice (or half) the one the uv lays: the shader turns their
// slopes to the relief as laid (30 degrees becomes 49.1, or 16.1), as the haptic chart does.
TEST(VisualMeshReference, ATextureSqueezedByTheUvIsSeenAtTheSlopeItIsLaidAt) {
  expectTiltedMapShading(2.0);
  expectTiltedMapShading(0.5);
}

// Pixels whose GPU hit lies deeper than half the relief: the march went down, not only along.
double deepFraction(const MeshFrame& frame, double max_depth_m) {
  int deep = 0, on = 0;
  for (int y = 0; y < frame.hits.height; ++y)
    for (int x = 0; x < frame.hits.width; ++x)
      if (frame.hits.at(x, y, 3) == 1.0f) ++on, deep += frame.hits.at(x, y, 2) > 0.5 * max_depth_m;
  return on ? double(deep) / on : 0.0;
}

// Pinned like test_relief_reference.cpp: the bounds are the values measured with Mesa 22.3.6
// llvmpipe plus a margin; the search is deterministic.
TEST(VisualMeshReference, ReliefOnACylinder) {
  // The box-shaped step of the plane's relief tests, 1 mm deep (24 of 64 texels raised), on a
  // 3 cm tube with a 3 cm tile; seen across the tube and obliquely from above.
  const OwnedSurface step = boxStep(64, 24, 0.03, 0.001);
  const TexturedTestMesh t = texturedMesh(mesh::cylinder(0.03, 0.06, 128, 8, 0.03), *step.map, true);
  RenderSettings settings = referenceLighting(SurfaceMode::Relief);
  settings.steps = {16, 6, 0};
  const Camera side_camera = orbitCamera(10, -80, 0.08, {0, 0, 0.03});
  const MeshComparison side = meshAgainstReference("relief cylinder side", t.surface, settings, side_camera);
  const MeshComparison above =
      meshAgainstReference("relief cylinder oblique", t.surface, settings, orbitCamera(50, -60, 0.08, {0, 0, 0.03}));
  EXPECT_GT(side.stats.compared, kImageSide * kImageSide / 2);
  EXPECT_GT(above.stats.compared, kImageSide * kImageSide / 4);  // through the open top: the background
  for (const MeshComparison* c : {&side, &above}) {
    EXPECT_LE(c->stats.otherTexelFraction(), 0.002);  // measured 0.0000, 0.0007
    EXPECT_LE(c->stats.meanError(), 0.02);            // 0.000, 0.001
    EXPECT_LE(c->mean_depth_error_m, 0.1 * finalInterval(*t.map, settings.steps));  // 1.7e-8, 3.9e-8 m
  }
  EXPECT_GT(deepFraction(renderMesh(t.surface, settings, side_camera), t.map->maxDepth()), 0.5);
}

TEST(VisualMeshReference, ReliefWithShadowsOnASphere) {
  const TexturedTestMesh t = texturedMesh(mesh::sphere(0.04, 96, 48, 0.06), generatedMap("bricks", 128, {}, 0.06), true);
  RenderSettings settings = referenceLighting(SurfaceMode::Relief);
  settings.steps = {16, 6, 8};
  const MeshComparison c = meshAgainstReference("relief sphere, 8 shadow steps", t.surface, settings,
                                                orbitCamera(35, -60, 0.11, Eigen::Vector3d::Zero()));
  EXPECT_GT(c.stats.compared, kImageSide * kImageSide / 2);
  // Each face marches at its own metres per uv (mesh::metresPerUv), which steps between the
  // sphere's rings: a pixel on a face edge that the rasteriser and the ray caster give to
  // different faces lands on other texels (0.0021 and 0.066 LSB with one tile size for the mesh).
  EXPECT_LE(c.stats.otherTexelFraction(), 0.005);  // measured 0.0037
  // 0.251: 8 samples towards the light put some shadow edges a sample off (the plane's too)
  EXPECT_LE(c.stats.meanError(), 0.35);
  EXPECT_LE(c.mean_depth_error_m, finalInterval(*t.map, settings.steps));  // 1.1e-6 m
}

}  // namespace
}  // namespace thx::visual::testing::test_mesh_reference
