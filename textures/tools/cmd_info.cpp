// texturetool info: what a texture file holds.
#include <cstdio>

#include "textures/green_convention.hpp"
#include "textures/import/normal_import.hpp"
#include "textures/texture_io.hpp"
#include "textures/texture_stats.hpp"
#include "textures/tools/cli.hpp"

namespace thx::tex::cli {

namespace {

// Our PNG through the loader; any other image as `import --alpha none` reads it.
TextureMap loadAnyFormat(const std::string& path, const LoadOptions& options, LoadReport& report,
                         std::vector<std::string>& warnings, const char*& format) {
  const DecodedImage decoded = readImage(path);
  format = toString(decoded.format);
  if (decoded.format == ImageFormat::Png) {
    TextureMap map = decodeTexture(decoded.image, path, options, &report);
    warnings = report.warnings;
    return map;
  }
  ImportOptions import;
  import.green = options.green;
  ImportReport imported;
  TextureMap map = importNormalMap(decoded, path, import, &imported);
  report = imported.texels;
  report.bit_depth = imported.bit_depth;
  warnings = imported.warnings;
  return map;
}

}  // namespace

int runInfo(const Args& args) {
  requirePositional(args, {"FILE"});
  const std::string& path = args.positional[0];
  LoadOptions options;
  options.green = parseGreen(args.get("--green"));
  if (const auto d = args.get("--max-depth")) options.max_depth_m = parseNumber("--max-depth", *d);
  // Repair so a damaged file is described rather than refused; the report says what was wrong.
  options.bad_texels = BadTexelPolicy::Repair;
  LoadReport report;
  std::vector<std::string> warnings;
  const char* format = "PNG";
  const TextureMap map = loadAnyFormat(path, options, report, warnings, format);

  TextureStats stats = computeStats(map);
  stats.bit_depth = report.bit_depth;
  const TextureMeta& meta = map.meta();
  std::printf("file:            %s\n", path.c_str());
  std::printf("format:          %s\n", format);
  std::printf("kind:            %s\n", meta.kind.c_str());
  if (meta.extent_x_m > 0.0) {
    std::printf("extent:          %.6g x %.6g m (texel %.6g x %.6g m)\n", meta.extent_x_m, meta.extent_y_m,
                meta.extent_x_m / map.width(), meta.extent_y_m / map.height());
  } else {
    std::printf("extent:          unknown\n");
  }
  if (!meta.params.empty()) std::printf("params:          %s\n", meta.params.c_str());
  std::printf("green read as:   %s\n", toString(options.green));
  const GreenGuess guess = guessGreenConvention(map, options.green);
  if (guess.convention) {
    std::printf("green likely:    %s (integrability score %+.2f%s)\n", toString(*guess.convention), guess.score,
                *guess.convention == options.green ? "" : "; read it with the other --green");
  } else {
    std::printf("green likely:    cannot tell (integrability score %+.2f: no mixed slopes to judge by)\n", guess.score);
  }
  std::fputs(formatStats(stats).c_str(), stdout);
  std::printf("bad texels:      %d degenerate, %d pointing into the surface (%d repaired for these statistics)\n",
              report.degenerate_texels, report.into_surface_texels, report.repaired_texels);
  for (const std::string& w : warnings) std::printf("warning:         %s\n", w.c_str());
  return 0;
}

}  // namespace thx::tex::cli
