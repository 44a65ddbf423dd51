#pragma once
// A texture from a built-in generator (textures/generators.hpp) at a given size and physical
// extent: what the renderer tests stroke.
#include <map>
#include <string>

#include "textures/generators.hpp"

namespace thx::test {

inline tex::TextureMap generatedTexture(const std::string& kind, std::map<std::string, double> params, int size,
                                        double extent_m) {
  tex::GenerateRequest r;
  r.kind = kind;
  r.size = size;
  r.params = std::move(params);
  r.params["extent"] = extent_m;
  return tex::generate(r);
}

}  // namespace thx::test
