#pragma once
// The shipped bowl of bricks (scenes/brick_bowl.yaml) as a scene's text, at a tessellation and a
// texture size of the test's choosing, followed by the test's own sections (device, objects,
// rates). Inside, the bowl is half an ellipsoid: semi-axes 55.2 mm across and 43.2 mm deep, its
// floor 4.8 mm above the bowl's frame (meshes/mesh_generators.cpp), the frame 4 cm below the
// world's origin.
#include <string>

namespace thx::test {

inline std::string bowlOfBricksScene(const std::string& name, int segments, int texels, const std::string& rest) {
  return "version: 1\nname: " + name +
         "\nsurface:\n"
         "  size: [0.04, 0.04]\n"
         "  mesh: {generator: bowl, size: 0.06, segments: " +
         std::to_string(segments) +
         ", closed: true}\n"
         "  pose: {position: [0.0, 0.0, -0.04], rpy_deg: [0.0, 0.0, 0.0]}\n"
         "  texture:\n"
         "    generator: bricks\n"
         "    size: " +
         std::to_string(texels) +
         "\n"
         "    params: {extent: 0.04, brick_length: 0.02, brick_height: 0.01, mortar: 0.0015, mortar_depth: 0.0008}\n"
         "  representation: relief\n"
         "  material: ceramic\n" +
         rest;
}

}  // namespace thx::test
