#pragma once
// A scenes folder of the test's own for scene-switch tests: shipped scenes copied under new names
// with their generated textures at 64 texels instead of 512 (fast to build; the name and the
// fingerprint are all a switch compares), and the identity hello_t would announce for each.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "scenes/scene_loader.hpp"
#include "scenes/scene_surface.hpp"
#include "thx_client/scene_check.hpp"

namespace thx::test {

// Writes DIR/NAME.yaml: scenes/SHIPPED.yaml with `size: 512` (the texture's texels) made 64.
inline std::string writeSmallScene(const std::filesystem::path& dir, const std::string& name, const std::string& shipped) {
  std::ifstream in(std::string(THX_SOURCE_DIR) + "/scenes/" + shipped + ".yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const std::string from = "size: 512", to = "size: 64";
  for (auto at = yaml.find(from); at != std::string::npos; at = yaml.find(from, at + to.size())) yaml.replace(at, from.size(), to);
  std::filesystem::create_directories(dir);
  const std::string file = (dir / (name + ".yaml")).string();
  std::ofstream(file) << yaml;
  return file;
}

// The scene as hapticd would announce it after loading `file` (scene_surface.hpp).
inline client::SceneIdentity identityOf(const std::string& file) {
  const scene::SceneSurface s = scene::buildSceneSurface(scene::loadScene(file));
  return {s.scene_name, s.fingerprint};
}

}  // namespace thx::test
