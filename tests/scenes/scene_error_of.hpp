#pragma once
// The loader's whole message for a scene text, or "" when it loads: the scene tests' way of
// checking that an error names the file, the field, the expectation and the value.
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

}  // namespace thx::test
