#pragma once
// Loading and saving textures as PNG (docs/textures.md has the file format).
//
//  RGB  -> normal map;  RGBA -> relief map (alpha = depth: 0 at the plane, max = deepest).
//  8- or 16-bit. Channel value c decodes to n = 2c/max - 1 per axis; the green channel's sign
//  follows the chosen convention (OpenGL: +Y up, DirectX: -Y).
//  Text chunks: "thx.kind", "thx.max_depth_m", "thx.extent_m" ("x y"), "thx.params".
//
// Bad texels: a decoded vector whose length is outside [0.5, 1.5] is degenerate; one with
// n.z <= 0 points into the surface. Policy Reject (default) refuses the file naming the first bad
// texel and the count; policy Repair replaces each bad texel with the renormalised mean of its
// valid 8-neighbours (or (0,0,1) if none) and reports the count.
#include <optional>
#include <string>
#include <vector>

#include "textures/png_io.hpp"
#include "textures/texture_map.hpp"

namespace thx::tex {

enum class GreenConvention { OpenGL, DirectX };
enum class BadTexelPolicy { Reject, Repair };

struct LoadOptions {
  GreenConvention green = GreenConvention::OpenGL;
  BadTexelPolicy bad_texels = BadTexelPolicy::Reject;
  std::optional<double> max_depth_m;            // overrides the file's thx.max_depth_m
  std::optional<Representation> representation;  // require this representation (error if the file differs);
                                                 // a relief file read as Normal drops its depth
};

struct LoadReport {
  int degenerate_texels = 0;
  int into_surface_texels = 0;
  int repaired_texels = 0;
  int bit_depth = 0;
  std::vector<std::string> warnings;
};

TextureMap loadTexture(const std::string& path, const LoadOptions& options = {}, LoadReport* report = nullptr);
// The same from an image already in memory (`source` names it in errors and warnings): RGB or
// RGBA, 8 or 16 bits, text chunks as in a PNG. The importer of other formats uses it.
TextureMap decodeTexture(const RawImage& raw, const std::string& source, const LoadOptions& options = {},
                         LoadReport* report = nullptr);

struct SaveOptions {
  int bit_depth = 16;  // 8 or 16
  GreenConvention green = GreenConvention::OpenGL;
};
void saveTexture(const std::string& path, const TextureMap& map, const SaveOptions& options = {});
// What saveTexture writes, as an image in memory (`source` names it in errors).
RawImage encodeTexture(const TextureMap& map, const std::string& source, const SaveOptions& options = {});

const char* toString(GreenConvention g);

}  // namespace thx::tex
