#pragma once
// The shipped grooved block's grooves (scenes/grooved_block.yaml: rounded U grooves 4 mm apart and
// 0.8 mm deep on a 2 cm tile, 64 texels), for tests that give a box its texture as a file.
#include <Eigen/Core>

#include "textures/generators.hpp"
#include "textures/height_normals.hpp"
#include "textures/texture_map.hpp"

namespace thx::test {

inline constexpr double kBlockGroovesTileM = 0.02, kBlockGroovesDepthM = 0.0008;
inline constexpr int kBlockGroovesTexels = 64;

// As the generator makes them: its normals are the profile's exact slopes.
inline tex::TextureMap generatedBlockGrooves() {
  tex::GenerateRequest request;
  request.kind = "grooves";
  request.size = kBlockGroovesTexels;
  request.params = {{"extent", kBlockGroovesTileM}, {"period", 0.004}, {"width", 0.004}, {"depth", kBlockGroovesDepthM}};
  return tex::generate(request);
}

// The same heights with normals from their central differences (the project's heights-to-normals
// rule, which integrating normals inverts): a relief, or its normals alone.
inline tex::TextureMap centralDifferenceBlockGrooves(tex::Representation representation) {
  const tex::TextureMap grooves = generatedBlockGrooves();
  tex::HeightField field(grooves.width(), grooves.height());
  for (int j = 0; j < field.height; ++j)
    for (int i = 0; i < field.width; ++i) field.at(i, j) = -double(grooves.depth(i, j));
  tex::ReliefFromHeightOptions options;
  options.texel_m = Eigen::Vector2d::Constant(kBlockGroovesTileM / kBlockGroovesTexels);
  options.address = tex::Address::Wrap;
  options.representation = representation;
  return tex::reliefFromHeight(field, options);
}

}  // namespace thx::test
