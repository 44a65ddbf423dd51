#pragma once
// Seeded procedural relief maps. Every generator defines a continuous height field and writes
// both the depth (alpha) and the normals of that same field, so normals agree with the depth
// gradients (tests/textures checks this). Output is always a relief map; use it as a normal map
// by choosing representation: normal in a scene (depth is then ignored).
//
// Parameters are SI (metres, degrees where named *_deg). Every generator accepts `extent`
// (the physical side of the square texture, default 0.2 m) besides its own parameters.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "textures/texture_map.hpp"

namespace thx::tex {

struct GeneratorParam {
  std::string name;
  double default_value = 0.0;
  std::string unit;  // "m", "deg", "1" ...
  std::string description;
  double min_value = 0.0;  // inclusive valid range, checked by generate()
  double max_value = 0.0;
};

struct GeneratorSpec {
  std::string kind;  // "bricks", "vvalley", "grooves", "pebbles", "wood", "sine", "dimples", "tilted", "zigzag",
                     // "porcelain", "metal", "stone", "ceramic_tile"
  std::string description;
  std::vector<GeneratorParam> params;
};

struct GenerateRequest {
  std::string kind;
  int size = 512;  // texels per side
  std::map<std::string, double> params;  // missing ones take their defaults
  std::uint64_t seed = 1;
};

const std::vector<GeneratorSpec>& generatorSpecs();
const GeneratorSpec* findGenerator(const std::string& kind);  // nullptr if unknown

// Throws TextureError naming the generator, the parameter, its value and the valid range
// (unknown kind, unknown parameter, out-of-range or non-finite value, size out of range).
TextureMap generate(const GenerateRequest& request);

}  // namespace thx::tex
