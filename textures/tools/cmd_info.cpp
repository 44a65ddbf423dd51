// texturetool info: what a texture file holds.
#include <cstdio>

#include "textures/texture_io.hpp"
#include "textures/texture_stats.hpp"
#include "textures/tools/cli.hpp"

namespace thx::tex::cli {

int runInfo(const Args& args) {
  requirePositional(args, {"FILE"});
  const std::string& path = args.positional[0];
  LoadOptions options;
  options.green = parseGreen(args.get("--green"));
  if (const auto d = args.get("--max-depth")) options.max_depth_m = parseNumber("--max-depth", *d);
  // Repair so a damaged file is described rather than refused; the report says what was wrong.
  options.bad_texels = BadTexelPolicy::Repair;
  LoadReport report;
  const TextureMap map = loadTexture(path, options, &report);

  TextureStats stats = computeStats(map);
  stats.bit_depth = report.bit_depth;
  const TextureMeta& meta = map.meta();
  std::printf("file:            %s\n", path.c_str());
  std::printf("kind:            %s\n", meta.kind.c_str());
  if (meta.extent_x_m > 0.0) {
    std::printf("extent:          %.6g x %.6g m (texel %.6g x %.6g m)\n", meta.extent_x_m, meta.extent_y_m,
                meta.extent_x_m / map.width(), meta.extent_y_m / map.height());
  } else {
    std::printf("extent:          unknown\n");
  }
  if (!meta.params.empty()) std::printf("params:          %s\n", meta.params.c_str());
  std::printf("green read as:   %s\n", toString(options.green));
  std::fputs(formatStats(stats).c_str(), stdout);
  std::printf("bad texels:      %d degenerate, %d pointing into the surface (%d repaired for these statistics)\n",
              report.degenerate_texels, report.into_surface_texels, report.repaired_texels);
  for (const std::string& w : report.warnings) std::printf("warning:         %s\n", w.c_str());
  return 0;
}

}  // namespace thx::tex::cli
