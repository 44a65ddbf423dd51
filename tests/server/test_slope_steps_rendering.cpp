// The servo's renderers with a texture's slope steps (textures/texel_slope_steps.hpp) render the
// same forces, to the bit, as without them: where the steps show a texel's neighbours within the
// crease angle, the plane renderer takes the interpolated plane without reading them, which is
// what reading them would have ended in. Strokes over V-valleys (creases and ridges), smooth
// bumps, a normal map, slopes scaled by a chart, a clamped map's border, and a textured sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "meshes/mesh_generators.hpp"
#include "server/proxy_renderer.hpp"
#include "server/textured_mesh_renderer.hpp"
#include "tests/support/generated_texture.hpp"
#include "textures/texel_slope_steps.hpp"

namespace test_slope_steps_rendering {

using namespace thx;

constexpr double kExtent = 0.05;

tex::TextureMap generated(const std::string& kind, std::map<std::string, double> params, int size = 128) {
  return test::generatedTexture(kind, std::move(params), size, kExtent);
}

srv::RendererConfig config() {
  srv::RendererConfig c;
  c.stiffness_n_per_m = 800.0;
  c.recovery_ticks = 10;
  return c;
}

// A stroke 20 mm/s at 1 kHz across the map, dipping in and out of the surface, running past a
// clamped map's border: every tick's output of both renderers compared.
struct Counts {
  int ticks = 0, contact = 0, skipped = 0, read = 0;
};
Counts strokeBoth(const tex::TexturedSurface& with, const tex::TexturedSurface& without, const srv::RendererConfig& c) {
  srv::ProxyRenderer a(with, c), b(without, c);
  const double sine = 0.5 * std::sin(c.crease_angle_deg * std::numbers::pi / 180.0);
  Counts n;
  for (int k = 0; k < 3000; ++k) {
    const double s = 2e-5 * k;
    const Eigen::Vector3d tip(-0.03 + s, 0.004 * std::sin(s / 0.007), -0.0012 + 0.0015 * std::cos(s / 0.005));
    const Eigen::Vector3d v(0.02, 0.0, 0.0);
    const srv::RenderOutput x = a.render(tip, v), y = b.render(tip, v);
    ++n.ticks;
    EXPECT_EQ(x.force_world, y.force_world) << "tick " << k;
    EXPECT_EQ(x.proxy_world, y.proxy_world) << "tick " << k;
    EXPECT_EQ(x.num_planes, y.num_planes) << "tick " << k;
    EXPECT_EQ(x.active_mask, y.active_mask) << "tick " << k;
    EXPECT_EQ(x.recovering, y.recovering) << "tick " << k;
    if (::testing::Test::HasFailure()) return n;
    n.contact += x.in_contact ? 1 : 0;
    if (!x.proxy_held) continue;
    long long i = 0, j = 0;
    const Eigen::Vector3d p = with.toLocal(x.proxy_world);
    with.texelContaining(p.x(), p.y(), i, j);
    (with.neighboursTurnWithin(i, j, sine) ? n.skipped : n.read) += 1;
  }
  return n;
}

struct Surfaces {
  tex::TextureMap map;
  tex::TexelSlopeSteps steps;
  tex::TexturedSurface with, without;
  Surfaces(tex::TextureMap m, tex::Address address, bool relief, double made_for_x = 0.0)
      : map(std::move(m)), steps(map) {
    tex::PlaneMapping mapping;
    mapping.size_m = {kExtent, kExtent};
    without = tex::TexturedSurface(map, mapping, {tex::Filter::Bilinear, address}, relief);
    if (made_for_x > 0.0) without.setNormalsMadeFor({made_for_x, kExtent});
    with = without;
    with.setSlopeSteps(&steps);
  }
};

TEST(SlopeStepsRendering, VValleysOnAClampedReliefRenderTheSameForcesWithAndWithoutTheSteps) {
  // 41 texels a period: the tiles of the steps (4 x 4 texels) away from the floors and ridges
  // hold none of them.
  const Surfaces s(generated("vvalley", {{"angle_deg", 60.0}, {"period", 0.004}}, 512), tex::Address::Clamp, true);
  ASSERT_NE(s.with.slopeSteps(), nullptr);
  ASSERT_EQ(s.without.slopeSteps(), nullptr);
  const Counts n = strokeBoth(s.with, s.without, config());
  EXPECT_GT(n.contact, 1000);
  // The walls' texels skip their neighbourhood, the floors' and ridges' read it.
  EXPECT_GT(n.skipped, 100);
  EXPECT_GT(n.read, 100);
}

TEST(SlopeStepsRendering, SmoothBumpsAndANormalMapRenderTheSameForcesWithAndWithoutTheSteps) {
  const Surfaces bumps(generated("sine", {{"amplitude", 0.0005}, {"period", 0.01}}, 256), tex::Address::Wrap, true);
  const Counts a = strokeBoth(bumps.with, bumps.without, config());
  EXPECT_GT(a.contact, 1000);
  EXPECT_EQ(a.read, 0);  // no crease anywhere on the bumps: every held tick skips the reading
  const Surfaces pebbles(generated("pebbles", {}), tex::Address::Wrap, false);
  const Counts b = strokeBoth(pebbles.with, pebbles.without, config());
  EXPECT_GT(b.contact, 1000);
  EXPECT_GT(b.skipped, 100);
}

TEST(SlopeStepsRendering, SlopesScaledByAChartAreBoundedByTheirLargestScale) {
  // Normals made for a tile three times the size laid here: slopes three times as steep along x,
  // so texels whose unscaled steps pass the angle no longer do.
  const Surfaces plain(generated("sine", {{"amplitude", 0.0005}, {"period", 0.01}}, 256), tex::Address::Wrap, true);
  const Surfaces steep(generated("sine", {{"amplitude", 0.0005}, {"period", 0.01}}, 256), tex::Address::Wrap, true,
                       3 * kExtent);
  const Counts a = strokeBoth(plain.with, plain.without, config());
  const Counts b = strokeBoth(steep.with, steep.without, config());
  EXPECT_GT(b.contact, 1000);
  EXPECT_GT(b.skipped, 0);
  EXPECT_EQ(a.read, 0);
  EXPECT_GT(b.read, 100);
}

TEST(SlopeStepsRendering, ATexturedSphereRendersTheSameForcesWithAndWithoutTheSteps) {
  const tex::TextureMap map = generated("vvalley", {{"angle_deg", 45.0}, {"period", 0.004}}, 512);
  const tex::TexelSlopeSteps steps(map);
  const mesh::TexturedMesh sphere = mesh::sphere(0.03, 48, 24, kExtent).mesh;
  const srv::TriangleBvh bvh(sphere.positions, sphere.triangles);
  srv::MeshTexture without{&map, {tex::Filter::Bilinear, tex::Address::Wrap}, true};
  srv::MeshTexture with = without;
  with.slope_steps = &steps;
  srv::TexturedMeshRenderer a(sphere, bvh, with, Eigen::Isometry3d::Identity(), config());
  srv::TexturedMeshRenderer b(sphere, bvh, without, Eigen::Isometry3d::Identity(), config());
  int contact = 0;
  for (int k = 0; k < 3000; ++k) {
    const double t = 1e-3 * k;  // along a latitude, in and out of the relief
    const double r = 0.03 - 0.0005 + 0.0007 * std::sin(t * 7.0);
    const Eigen::Vector3d tip(r * std::cos(t) * 0.95, r * std::sin(t) * 0.95, r * 0.31);
    const srv::RenderOutput x = a.render(tip, Eigen::Vector3d::Zero());
    const srv::RenderOutput y = b.render(tip, Eigen::Vector3d::Zero());
    ASSERT_EQ(x.force_world, y.force_world) << "tick " << k;
    ASSERT_EQ(x.proxy_world, y.proxy_world) << "tick " << k;
    ASSERT_EQ(x.num_planes, y.num_planes) << "tick " << k;
    contact += x.in_contact ? 1 : 0;
  }
  EXPECT_GT(contact, 1000);
}

}  // namespace test_slope_steps_rendering
