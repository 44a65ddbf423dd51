// texturetool import: a JPEG, TGA, BMP, TIFF, WebP or PNG normal map from elsewhere -> our PNG.
#include <cstdio>

#include "textures/import/normal_import.hpp"
#include "textures/texture_io.hpp"
#include "textures/tools/cli.hpp"

namespace thx::tex::cli {

namespace {

AlphaMeaning parseAlpha(const std::optional<std::string>& text) {
  if (!text || *text == "none") return AlphaMeaning::None;
  if (*text == "height") return AlphaMeaning::Height;
  if (*text == "depth") return AlphaMeaning::Depth;
  throw UsageError("--alpha: '" + *text + "'; expected none, height or depth");
}

}  // namespace

int runImport(const Args& args) {
  requirePositional(args, {"IN", "OUT"});
  const std::string& in = args.positional[0];
  const std::string& out = args.positional[1];
  ImportOptions options;
  options.green = parseGreen(args.get("--green"));
  options.alpha = parseAlpha(args.get("--alpha"));
  if (const auto s = args.get("--alpha-scale")) {
    if (options.alpha == AlphaMeaning::None) throw UsageError("--alpha-scale needs --alpha height or --alpha depth");
    options.alpha_scale_m = parseNumber("--alpha-scale", *s);
  }
  if (const auto e = args.get("--extent")) {
    options.extent_m = parseNumber("--extent", *e);
    if (!(options.extent_m > 0.0)) throw UsageError("--extent: must be > 0 metres");
  }
  if (const auto m = args.get("--max-pixels")) {
    const int n = parseInt("--max-pixels", *m);
    if (n < kMinTextureSide * kMinTextureSide || n > kMaxImagePixels)
      throw UsageError("--max-pixels: '" + *m + "'; expected 4 (2 x 2) to 268435456 (16384 x 16384)");
    options.max_pixels = n;
  }
  SaveOptions save;
  save.bit_depth = parseBits(args.get("--bits"), 16);
  save.green = GreenConvention::OpenGL;

  ImportReport report;
  const TextureMap map = importNormalMapFile(in, options, &report);
  for (const std::string& w : report.warnings) std::fprintf(stderr, "texturetool import: warning: %s\n", w.c_str());
  saveTexture(out, map, save);
  std::printf("wrote %s: %s map %dx%d, %d-bit, green opengl, from %s (%d channels, %d-bit, green read as %s, "
              "alpha %s)",
              out.c_str(), toString(map.representation()), map.width(), map.height(), save.bit_depth,
              toString(report.format), report.channels, report.bit_depth, toString(options.green),
              toString(options.alpha));
  if (map.isRelief()) std::printf(", max depth %.6g m", map.maxDepth());
  std::printf("; %zu warning(s)\n", report.warnings.size());
  return 0;
}

}  // namespace thx::tex::cli
