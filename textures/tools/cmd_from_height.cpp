// texturetool from-height: grayscale height image -> relief or normal map.
#include <cstdio>

#include "textures/height_normals.hpp"
#include "textures/png_io.hpp"
#include "textures/texture_error.hpp"
#include "textures/texture_io.hpp"
#include "textures/tools/cli.hpp"

namespace thx::tex::cli {

int runFromHeight(const Args& args) {
  requirePositional(args, {"IN", "OUT"});
  const std::string& in = args.positional[0];
  const std::string& out = args.positional[1];
  const double extent = parseNumber("--extent", args.require("--extent"));
  if (!(extent > 0.0)) throw UsageError("--extent: must be > 0 metres");
  const double range = args.has("--height-range") ? parseNumber("--height-range", *args.get("--height-range")) : 0.001;
  if (!(range >= 0.0)) throw UsageError("--height-range: must be >= 0 metres");
  ReliefFromHeightOptions options;
  if (const auto r = args.get("--representation")) {
    if (*r == "relief") {
      options.representation = Representation::Relief;
    } else if (*r == "normal") {
      options.representation = Representation::Normal;
    } else {
      throw UsageError("--representation: '" + *r + "'; expected relief or normal");
    }
  }
  options.address = parseAddress(args.get("--address"), Address::Clamp);
  SaveOptions save;
  save.bit_depth = parseBits(args.get("--bits"), 16);
  save.green = parseGreen(args.get("--green"));

  const RawImage image = readPng(in);
  if (image.channels != 1) {
    static const char* kLayouts[] = {"", "grayscale", "grayscale + alpha", "RGB", "RGBA"};
    const char* layout = image.channels >= 1 && image.channels <= 4 ? kLayouts[image.channels] : "unknown";
    throw TextureError(in, "a height image must be grayscale",
                       std::to_string(image.channels) + " channels (" + layout + ")",
                       "1 channel (8- or 16-bit grayscale PNG, white = high)");
  }
  HeightField field(image.width, image.height);
  const double scale = range / image.maxValue();
  for (int j = 0; j < image.height; ++j) {
    for (int i = 0; i < image.width; ++i) field.at(i, j) = image.at(i, j, 0) * scale;
  }
  const double texel = extent / image.width;  // square texels
  options.texel_m = {texel, texel};
  options.source = in;
  TextureMap map = reliefFromHeight(field, options);
  char white[32];
  std::snprintf(white, sizeof white, "%.9g", range);
  map.meta().params = "from=" + in + " white_m=" + white + " bits_in=" + std::to_string(image.bit_depth) + " " +
                      map.meta().params;
  saveTexture(out, map, save);
  std::printf("wrote %s: %s map %dx%d, %d-bit, extent %.6g x %.6g m, max depth %.6g m\n", out.c_str(),
              toString(map.representation()), map.width(), map.height(), save.bit_depth, map.meta().extent_x_m,
              map.meta().extent_y_m, map.maxDepth());
  return 0;
}

}  // namespace thx::tex::cli
