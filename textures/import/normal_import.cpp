#include "textures/import/normal_import.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "textures/texture_error.hpp"

namespace thx::tex {

namespace {

std::string percent(double fraction) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f %%", 100.0 * fraction);
  return buf;
}

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

void checkOptions(const std::string& source, const DecodedImage& decoded, const ImportOptions& options) {
  const int channels = decoded.image.channels;
  if (channels < 3) {
    throw TextureError(source, "a normal map needs colour channels",
                       std::to_string(channels) + (channels == 1 ? " channel (grayscale)" : " channels (grayscale + alpha)"),
                       "RGB or RGBA (for a height image use texturetool from-height)");
  }
  if (options.alpha == AlphaMeaning::None) return;
  if (channels != 4) {
    throw TextureError(source, std::string("alpha given as ") + toString(options.alpha) + " but the image has no alpha",
                       std::to_string(channels) + " channels (RGB)", "an RGBA image, or --alpha none");
  }
  if (!options.alpha_scale_m) {
    throw TextureError(source, std::string("alpha given as ") + toString(options.alpha) + " without its scale",
                       "no alpha scale", "the metres from alpha 0 to full alpha (texturetool: --alpha-scale M)");
  }
  const double s = *options.alpha_scale_m;
  if (!std::isfinite(s) || s <= 0.0 || s > kMaxAlphaScaleM) {
    throw TextureError(source, "alpha scale out of range", number(s) + " m", "a depth in (0, " + number(kMaxAlphaScaleM) + "] m");
  }
}

void measureNormals(const RawImage& image, ImportReport& rep) {
  const double scale = 2.0 / image.maxValue();
  double sum = 0.0;
  std::size_t far = 0;
  const std::size_t count = std::size_t(image.width) * std::size_t(image.height);
  for (int j = 0; j < image.height; ++j) {
    for (int i = 0; i < image.width; ++i) {
      const double x = image.at(i, j, 0) * scale - 1.0, y = image.at(i, j, 1) * scale - 1.0,
                   z = image.at(i, j, 2) * scale - 1.0;
      const double len = std::sqrt(x * x + y * y + z * z);
      sum += len;
      if (std::fabs(len - 1.0) > kUnitLengthTolerance) ++far;
    }
  }
  rep.mean_length = sum / double(count);
  rep.far_from_unit_fraction = double(far) / double(count);
}

void measureAlpha(const RawImage& image, ImportReport& rep) {
  int lo = image.maxValue(), hi = 0;
  for (int j = 0; j < image.height; ++j) {
    for (int i = 0; i < image.width; ++i) {
      lo = std::min<int>(lo, image.at(i, j, 3));
      hi = std::max<int>(hi, image.at(i, j, 3));
    }
  }
  rep.alpha_min = lo;
  rep.alpha_max = hi;
}

// The image in our PNG layout: RGB as read, alpha turned into depth (0 = plane) when kept.
RawImage toProjectLayout(const RawImage& in, const ImportOptions& options) {
  const bool keep_alpha = options.alpha != AlphaMeaning::None;
  RawImage out;
  out.width = in.width;
  out.height = in.height;
  out.bit_depth = in.bit_depth;
  out.channels = keep_alpha ? 4 : 3;
  out.samples.resize(std::size_t(out.width) * std::size_t(out.height) * std::size_t(out.channels));
  const std::uint16_t max = std::uint16_t(in.maxValue());
  std::size_t k = 0;
  for (int j = 0; j < in.height; ++j) {
    for (int i = 0; i < in.width; ++i) {
      for (int c = 0; c < 3; ++c) out.samples[k++] = in.at(i, j, c);
      if (!keep_alpha) continue;
      const std::uint16_t a = in.at(i, j, 3);
      out.samples[k++] = options.alpha == AlphaMeaning::Height ? std::uint16_t(max - a) : a;
    }
  }
  return out;
}

void warnAbout(const std::string& source, const ImportOptions& options, ImportReport& rep) {
  if (rep.channels == 4) {
    const std::string range = std::to_string(rep.alpha_min) + (rep.alpha_min == rep.alpha_max ? "" : ".." + std::to_string(rep.alpha_max));
    if (options.alpha != AlphaMeaning::None && rep.alpha_min == rep.alpha_max) {
      rep.warnings.push_back(source + ": alpha is " + range + " everywhere, so the " + toString(options.alpha) +
                             " it was said to hold is flat (an RGBA normal map with an unused alpha?); "
                             "import with --alpha none for a normal map");
    } else if (options.alpha == AlphaMeaning::None && rep.alpha_min != rep.alpha_max) {
      rep.warnings.push_back(source + ": alpha varies (" + range + ") and was dropped; if it holds height or depth, "
                             "import with --alpha height|depth --alpha-scale M to keep it as a relief map");
    }
  }
  if (rep.far_from_unit_fraction > kFarFromUnitFraction) {
    rep.warnings.push_back(source + ": normals far from unit length: mean |n| = " + number(rep.mean_length) + ", " +
                           percent(rep.far_from_unit_fraction) + " of texels off by more than " +
                           percent(kUnitLengthTolerance) +
                           " (renormalised; expected RGB = (n + 1)/2 per channel; is this a normal map?)");
  }
  for (const std::string& w : rep.texels.warnings) rep.warnings.push_back(w);
  if (rep.green_guess.convention && *rep.green_guess.convention != options.green) {
    rep.warnings.push_back(source + ": the normals look like " + toString(*rep.green_guess.convention) +
                           " green (integrability score " + number(rep.green_guess.score) + ") but were read as " +
                           toString(options.green) + "; import with --green " +
                           toString(*rep.green_guess.convention) + " if the relief looks inside out");
  }
}

}  // namespace

const char* toString(AlphaMeaning alpha) {
  switch (alpha) {
    case AlphaMeaning::None: return "none";
    case AlphaMeaning::Height: return "height";
    case AlphaMeaning::Depth: return "depth";
  }
  return "none";
}

TextureMap importNormalMap(const DecodedImage& decoded, const std::string& source, const ImportOptions& options,
                           ImportReport* report) {
  ImportReport local;
  ImportReport& rep = report ? *report : local;
  rep = ImportReport{};
  const RawImage& in = decoded.image;
  rep.format = decoded.format;
  rep.channels = in.channels;
  rep.bit_depth = in.bit_depth;
  checkOptions(source, decoded, options);
  measureNormals(in, rep);
  if (in.channels == 4) measureAlpha(in, rep);

  LoadOptions load;
  load.green = options.green;
  load.bad_texels = BadTexelPolicy::Repair;  // reported, never silent
  if (options.alpha != AlphaMeaning::None) load.max_depth_m = options.alpha_scale_m;
  TextureMap map = decodeTexture(toProjectLayout(in, options), source, load, &rep.texels);
  TextureMeta& meta = map.meta();
  meta.kind = "imported";
  meta.params = std::string("from=") + source + " format=" + toString(decoded.format) + " bits=" +
                std::to_string(in.bit_depth) + " green=" + toString(options.green) + " alpha=" + toString(options.alpha);
  if (options.extent_m > 0.0) {
    meta.extent_x_m = options.extent_m;
    meta.extent_y_m = options.extent_m * map.height() / map.width();
  }
  rep.green_guess = guessGreenConvention(map, options.green);
  warnAbout(source, options, rep);
  return map;
}

TextureMap importNormalMapFile(const std::string& path, const ImportOptions& options, ImportReport* report) {
  return importNormalMap(readImage(path, options.max_pixels), path, options, report);
}

}  // namespace thx::tex
