#pragma once
// Shared by the visual reference tests: one headless context per test process (llvmpipe capped
// at 2 threads), surfaces built in memory, a render of the plane alone with the lighting the
// references use (one directional light, no ambient, no specular, white albedo), and the
// comparison of every surface pixel against referenceHit().
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <memory>

#include "clients/visual/cpu_reference.hpp"
#include "clients/visual/frame_renderer.hpp"
#include "clients/visual/headless_context.hpp"
#include "textures/generators.hpp"
#include "textures/height_normals.hpp"

namespace thx::visual::testing {

inline HeadlessContext& context() {
  static std::unique_ptr<HeadlessContext> c = [] {
    setenv("LP_NUM_THREADS", "2", 0);  // two cores here; an explicit setting wins
    return std::make_unique<HeadlessContext>();
  }();
  return *c;
}

inline constexpr int kImageSide = 128;

inline RenderSettings referenceLighting(SurfaceMode mode) {
  RenderSettings s;
  s.mode = mode;
  s.light = Lighting{40.0, -135.0, 0.0, 0.0};
  s.plane_albedo = Eigen::Vector3f::Ones();
  s.hit_buffer = true;
  return s;
}

struct PixelStats {
  int compared = 0;
  int other_texel = 0;   // GPU hit on another texel than the reference's
  double sum_error = 0;  // |GPU - reference| in 8-bit LSB
  int max_error = 0;
  double otherTexelFraction() const { return compared ? double(other_texel) / compared : 1.0; }
  double meanError() const { return compared ? sum_error / compared : 1e9; }
};

// Renders the surface alone and compares every pixel whose reference ray meets the map, skipping
// pixels next to the map's border or the background (partial coverage there).
inline PixelStats compareWithReference(const tex::TexturedSurface& surface, const RenderSettings& settings,
                                       const CameraPlacement& placement) {
  context();
  FrameRenderer renderer(surface, settings, kImageSide, kImageSide);
  const Camera camera(placement, surface.mapping().plane_to_world, kImageSide, kImageSide);
  renderer.render(camera, {});
  const Rgba8Image colour = renderer.framebuffer().readColour();
  const FloatImage hits = renderer.framebuffer().readHits();

  ReferenceLight light{lightDirectionLocal(settings.light), settings.steps.shadow > 0};
  const bool relief = settings.mode == SurfaceMode::Relief;
  std::vector<std::optional<ReferenceHit>> ref(std::size_t(kImageSide) * kImageSide);
  for (int y = 0; y < kImageSide; ++y)
    for (int x = 0; x < kImageSide; ++x)
      ref[std::size_t(y) * kImageSide + x] = referenceHit(surface, camera.pixelRay(x, y), relief, light);

  PixelStats stats;
  for (int y = 1; y + 1 < kImageSide; ++y)
    for (int x = 1; x + 1 < kImageSide; ++x) {
      bool interior = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) interior = interior && ref[std::size_t(y + dy) * kImageSide + x + dx];
      if (!interior) continue;
      const ReferenceHit& r = *ref[std::size_t(y) * kImageSide + x];
      EXPECT_EQ(hits.at(x, y, 3), 1.0f) << "pixel " << x << "," << y << " is not the surface";
      const tex::TexelIndex gpu_texel =
          tex::texelOf(surface.map(), {hits.at(x, y, 0), hits.at(x, y, 1)}, surface.sampling().address);
      const int expected = int(std::lround(255.0 * std::min(1.0, r.intensity)));
      const int error = std::abs(int(colour.at(x, y, 0)) - expected);
      ++stats.compared;
      stats.other_texel += gpu_texel == r.texel ? 0 : 1;
      stats.sum_error += error;
      stats.max_error = std::max(stats.max_error, error);
    }
  return stats;
}

// A surface that owns its map (TexturedSurface only points at it).
struct OwnedSurface {
  std::unique_ptr<tex::TextureMap> map;
  tex::TexturedSurface surface;
};

inline OwnedSurface place(tex::TextureMap map, double size_m) {
  OwnedSurface o{std::make_unique<tex::TextureMap>(std::move(map)), {}};
  tex::PlaneMapping mapping;
  mapping.size_m = {size_m, size_m};
  o.surface = tex::TexturedSurface(*o.map, mapping, tex::SampleOptions{}, true);
  return o;
}

inline OwnedSurface generated(const std::string& kind, int texels, std::map<std::string, double> params) {
  params["extent"] = 0.2;
  return place(tex::generate({kind, texels, params, 7}), 0.2);
}

// A raised square (`inner` texels a side, at the plane) in a field `depth_m` deeper: a box-shaped
// step, normals from the height field.
inline OwnedSurface boxStep(int texels, int inner, double size_m, double depth_m) {
  tex::HeightField h(texels, texels, -depth_m);
  const int lo = (texels - inner) / 2;
  for (int j = lo; j < lo + inner; ++j)
    for (int i = lo; i < lo + inner; ++i) h.at(i, j) = 0.0;
  tex::ReliefFromHeightOptions o;
  o.texel_m = Eigen::Vector2d::Constant(size_m / texels);
  o.address = tex::Address::Wrap;
  return place(tex::reliefFromHeight(h, o), size_m);
}

}  // namespace thx::visual::testing
