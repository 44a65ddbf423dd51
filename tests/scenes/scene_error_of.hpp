#pragma once
// The loader's whole message for a scene text, or "" when it loads: the scene tests' way of
// checking that an error names the file, the field, the expectation and the value. And the
// smallest plane scene, for tests that append a device section to it.
#include <string>

#include "scenes/scene_loader.hpp"

namespace thx::test {

inline std::string sceneErrorOf(const std::string& text) {
  try {
    scene::parseScene(text, "s.yaml", "");
  } catch (const scene::SceneError& e) {
    return e.what();
  }
  return "";
}

inline std::string planeSceneText(const std::string& name) {
  return "version: 1\nname: " + name + "\nsurface:\n  size: [0.2, 0.2]\n  texture: {generator: bricks}\n";
}

}  // namespace thx::test
