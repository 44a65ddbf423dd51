#pragma once
// Shared by the visual reference tests: one headless context per test process (llvmpipe capped
// at 2 threads), surfaces built in memory, a render of the plane alone with the lighting the
// references use (one directional light, no ambient, no specular, white albedo), and the
// comparison of every surface pixel against the CPU reference.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <memory>

#include "clients/visual/cpu_reference.hpp"
#include "clients/visual/frame_renderer.hpp"
#include "clients/visual/headless_context.hpp"
#include "clients/visual/image_error.hpp"
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

// Renders the surface alone and compares it with the CPU reference (image_error.hpp).
inline PixelStats compareWithReference(const tex::TexturedSurface& surface, const RenderSettings& settings,
                                       const CameraPlacement& placement) {
  context();
  FrameRenderer renderer(surface, settings, kImageSide, kImageSide);
  const Camera camera(placement, surface.mapping().plane_to_world, kImageSide, kImageSide);
  renderer.render(camera, {});
  const ReferenceLight light{lightDirectionLocal(settings.light), settings.steps.shadow > 0};
  const ReferenceImage reference = referenceImage(surface, camera, kImageSide, kImageSide,
                                                  settings.mode == SurfaceMode::Relief, light);
  const PixelStats stats = visual::compareWithReference(surface, reference, renderer.framebuffer().readColour(),
                                                        renderer.framebuffer().readHits());
  EXPECT_EQ(stats.not_surface, 0) << "pixels the reference sees on the surface and the frame does not";
  return stats;
}

// The relief tests' camera views (elevation above the plane, azimuth around its normal).
struct View {
  const char* name;
  double elevation_deg;
  double azimuth_deg;
};
inline constexpr View kSteep{"steep", 70, -100};
inline constexpr View kOblique{"oblique", 40, -60};
inline constexpr View kGrazing{"grazing", 15, -80};

// A relief render of `surface` from `view` against the exact reference, printed (the tests pin
// these numbers) and checked to cover enough pixels.
inline PixelStats reliefAgainstReference(const tex::TexturedSurface& surface, const View& view, double distance_m,
                                         ReliefSteps steps) {
  RenderSettings settings = referenceLighting(SurfaceMode::Relief);
  settings.steps = steps;
  CameraPlacement camera;
  camera.elevation_deg = view.elevation_deg;
  camera.azimuth_deg = view.azimuth_deg;
  camera.distance_m = distance_m;
  const PixelStats stats = compareWithReference(surface, settings, camera);
  std::printf("relief %-6s %-8s %2d+%d shadow %2d: %5d px, other texel %.4f, mean %.3f LSB, max %3d LSB\n",
              steps.search == ReliefSearch::MaxMip ? "maxmip" : "linear", view.name, steps.linear, steps.binary,
              steps.shadow, stats.compared, stats.otherTexelFraction(), stats.meanError(), stats.max_error);
  EXPECT_GT(stats.compared, kImageSide * kImageSide / 8) << view.name;
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
