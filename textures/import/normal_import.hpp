#pragma once
// Turning a third-party normal map (any format image_decode.hpp reads) into the project's
// TextureMap, which texturetool import then writes as our PNG (docs/textures.md, "Importing").
//
//  - RGB holds the normal, channel c -> 2c/max - 1, green read with `green` (DirectX flips it);
//    every normal is renormalised (TextureMap stores unit normals).
//  - Alpha holds what `alpha` says: nothing (dropped), height (white = high: depth =
//    (1 - a/max)·alpha_scale) or depth (white = deep: depth = a/max·alpha_scale); a kept alpha
//    makes a relief map whose maximum depth is alpha_scale metres.
//  - Warnings (never silent changes): a kept alpha that is constant (an RGBA normal map whose
//    alpha is unused would become a flat relief), a dropped alpha that varies, normals far from
//    unit length (not a normal map, or one with another encoding), bad texels repaired, and normals
//    that look like the other green convention (green_convention.hpp).
#include <optional>
#include <string>
#include <vector>

#include "textures/green_convention.hpp"
#include "textures/import/image_decode.hpp"
#include "textures/texture_io.hpp"
#include "textures/texture_map.hpp"

namespace thx::tex {

enum class AlphaMeaning { None, Height, Depth };
const char* toString(AlphaMeaning alpha);

struct ImportOptions {
  GreenConvention green = GreenConvention::OpenGL;
  AlphaMeaning alpha = AlphaMeaning::None;
  std::optional<double> alpha_scale_m;  // metres from alpha 0 to full alpha; required unless alpha None
  double extent_m = 0.0;                // physical width of the image, metres; 0 = unknown
  // Files of more pixels are refused, from the header where it says (image_decode.hpp); for the
  // file reader (importNormalMapFile): a DecodedImage was already checked by its decodeImage.
  std::int64_t max_pixels = kMaxImagePixels;
};

// Above these a map's normals are "far from unit length": more than kFarFromUnitFraction of its
// texels have | |n| - 1 | > kUnitLengthTolerance. A JPEG at quality 75 stays far below.
inline constexpr double kUnitLengthTolerance = 0.1;
inline constexpr double kFarFromUnitFraction = 0.05;
// Alpha scale accepted: (0, kMaxAlphaScaleM] metres.
inline constexpr double kMaxAlphaScaleM = 1.0;

struct ImportReport {
  ImageFormat format = ImageFormat::Png;
  int channels = 0;  // of the input
  int bit_depth = 0;
  int alpha_min = 0, alpha_max = 0;   // codes, when the input has alpha
  double mean_length = 0.0;           // mean decoded |n| before renormalisation
  double far_from_unit_fraction = 0;  // texels with | |n| - 1 | > kUnitLengthTolerance
  GreenGuess green_guess;             // about the file, relative to ImportOptions::green
  LoadReport texels;                  // bad texels (repaired) and their warnings
  std::vector<std::string> warnings;  // everything the user should read, file name first
};

TextureMap importNormalMap(const DecodedImage& decoded, const std::string& source, const ImportOptions& options,
                           ImportReport* report = nullptr);
TextureMap importNormalMapFile(const std::string& path, const ImportOptions& options, ImportReport* report = nullptr);

}  // namespace thx::tex
