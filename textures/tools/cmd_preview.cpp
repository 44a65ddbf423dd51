// texturetool preview: a shaded picture of a texture, for people who would rather look than read.
// Lambert shading of the sampled normals under a light from the upper left (azimuth 135 deg,
// elevation 45 deg); relief maps are also darkened with depth so grooves read as grooves.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "textures/png_io.hpp"
#include "textures/texture_io.hpp"
#include "textures/tools/cli.hpp"

namespace thx::tex::cli {

int runPreview(const Args& args) {
  requirePositional(args, {"IN", "OUT"});
  const std::string& in = args.positional[0];
  const std::string& out = args.positional[1];
  LoadOptions load;
  load.green = parseGreen(args.get("--green"));
  load.bad_texels = BadTexelPolicy::Repair;
  const double azimuth = args.has("--azimuth") ? parseNumber("--azimuth", *args.get("--azimuth")) : 135.0;
  const double elevation = args.has("--elevation") ? parseNumber("--elevation", *args.get("--elevation")) : 45.0;
  if (elevation <= 0.0 || elevation > 90.0) {
    throw UsageError("--elevation must be in (0, 90] degrees, got " + std::to_string(elevation));
  }
  LoadReport report;
  const TextureMap map = loadTexture(in, load, &report);
  const double az = azimuth * std::numbers::pi / 180.0, el = elevation * std::numbers::pi / 180.0;
  const Eigen::Vector3f light(float(std::cos(el) * std::cos(az)), float(std::cos(el) * std::sin(az)),
                              float(std::sin(el)));
  RawImage img;
  img.width = map.width();
  img.height = map.height();
  img.channels = 1;
  img.bit_depth = 8;
  img.samples.resize(std::size_t(img.width) * std::size_t(img.height));
  const float depth_scale = map.isRelief() ? float(1.0 / map.maxDepth()) : 0.0f;
  std::size_t k = 0;
  for (int j = 0; j < map.height(); ++j) {
    for (int i = 0; i < map.width(); ++i) {
      const float lambert = std::max(0.0f, map.normal(i, j).dot(light));
      const float occlusion = 1.0f - 0.35f * map.depth(i, j) * depth_scale;
      const float value = std::clamp(0.08f + 0.92f * lambert * occlusion, 0.0f, 1.0f);
      img.samples[k++] = std::uint16_t(std::lround(value * 255.0f));
    }
  }
  writePng(out, img);
  std::printf("wrote %s: %dx%d shaded preview of %s (light azimuth %.0f deg, elevation %.0f deg)\n", out.c_str(),
              img.width, img.height, in.c_str(), azimuth, elevation);
  return 0;
}

}  // namespace thx::tex::cli
