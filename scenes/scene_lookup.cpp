#include "scenes/scene_lookup.hpp"

#include <algorithm>
#include <filesystem>
#include <system_error>
#include <vector>

namespace thx::scene {

namespace fs = std::filesystem;

namespace {

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// The scene names a folder holds (stems of its *.yaml files), sorted; at most `limit` of them.
std::string sceneNamesIn(const fs::path& dir, std::size_t limit = 20) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() == ".yaml" && it->is_regular_file(ec)) names.push_back(it->path().stem().string());
  }
  std::sort(names.begin(), names.end());
  if (names.empty()) return "none";
  std::string out;
  for (std::size_t k = 0; k < names.size() && k < limit; ++k) out += (k ? ", " : "") + names[k];
  if (names.size() > limit) out += ", ... (" + std::to_string(names.size()) + " in all)";
  return out;
}

}  // namespace

bool isValidSceneName(const std::string& name) {
  if (name.empty() || name.size() > 100 || name.front() == '.') return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
           c == '.';
  });
}

void requireValidSceneName(const std::string& name) {
  if (!isValidSceneName(name))
    throw SceneLookupError("invalid scene name '" + name +
                           "': expected 1 to 100 characters of [A-Za-z0-9_.-], not starting with '.' (a scene "
                           "file's name without .yaml)");
}

std::string resolveSceneName(const std::string& name, const std::string& scenes_dir) {
  requireValidSceneName(name);
  const fs::path dir = scenes_dir.empty() ? fs::path(".") : fs::path(scenes_dir);
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw SceneLookupError("scene '" + name + "' not found: the scenes folder '" + dir.string() +
                           "' does not exist (name another with --scenes-dir DIR)");
  const fs::path file = dir / (name + ".yaml");
  if (!fs::is_regular_file(file, ec))
    throw SceneLookupError("scene '" + name + "' not found: no file " + file.string() +
                           " (name another folder with --scenes-dir DIR, or the file with --scene PATH); scenes in '" +
                           dir.string() + "': " + sceneNamesIn(dir));
  return file.string();
}

bool isScenePath(const std::string& scene_or_path) {
  return scene_or_path.find('/') != std::string::npos || endsWith(scene_or_path, ".yaml") ||
         endsWith(scene_or_path, ".yml");
}

std::string resolveSceneArgument(const std::string& scene_or_path, const std::string& scenes_dir) {
  if (!isScenePath(scene_or_path)) return resolveSceneName(scene_or_path, scenes_dir);
  std::error_code ec;
  if (!fs::is_regular_file(scene_or_path, ec))
    throw SceneLookupError("scene file '" + scene_or_path + "' does not exist");
  return scene_or_path;
}

}  // namespace thx::scene
