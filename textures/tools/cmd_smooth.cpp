// texturetool smooth: gradient-domain Gaussian smoothing (smoothing.hpp).
#include <cstdio>

#include "textures/smoothing.hpp"
#include "textures/texture_io.hpp"
#include "textures/tools/cli.hpp"

namespace thx::tex::cli {

int runSmooth(const Args& args) {
  requirePositional(args, {"IN", "OUT"});
  const std::string& in = args.positional[0];
  const std::string& out = args.positional[1];
  SmoothOptions options;
  options.sigma_texels = parseNumber("--sigma", args.require("--sigma"));
  options.address = parseAddress(args.get("--address"), Address::Wrap);
  LoadOptions load;
  load.green = parseGreen(args.get("--green"));
  LoadReport report;
  const TextureMap map = loadTexture(in, load, &report);
  for (const std::string& w : report.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());

  const TextureMap smoothed = smoothTexture(map, options);  // checks sigma's range
  SaveOptions save;
  save.bit_depth = parseBits(args.get("--bits"), report.bit_depth == 8 ? 8 : 16);
  save.green = load.green;
  saveTexture(out, smoothed, save);
  std::printf("wrote %s: %s map %dx%d smoothed with sigma %.6g texels (%s), %d-bit\n", out.c_str(),
              toString(smoothed.representation()), smoothed.width(), smoothed.height(), options.sigma_texels,
              options.address == Address::Wrap ? "wrap" : "clamp", save.bit_depth);
  return 0;
}

}  // namespace thx::tex::cli
