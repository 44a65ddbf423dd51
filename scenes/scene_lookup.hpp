#pragma once
// Where is the scene file of a name, on this host. A scene's name on the wire (hello_t.scene_name,
// server_command_t ACTION_LOAD_SCENE's argument) is its file's stem (scene::sceneName); every
// host finds it as NAME.yaml in its own scenes folder. hapticd resolves a client's scene switch
// here, the clients resolve the server's hello here (thx_client/scene_check.hpp re-exports these).
#include <string>

#include "base/error.hpp"

namespace thx::scene {

class SceneLookupError : public thx::Error {
 public:
  explicit SceneLookupError(const std::string& what) : thx::Error(Kind::Config, what) {}
};

// A scene name is 1..100 characters of [A-Za-z0-9_.-], not starting with '.': a file stem, never
// a path (a name from the network cannot reach outside the scenes folder).
bool isValidSceneName(const std::string& name);
// Throws SceneLookupError naming the name and the rules when !isValidSceneName(name).
void requireValidSceneName(const std::string& name);

// The file of scene NAME in `scenes_dir`: scenes_dir/NAME.yaml. Throws SceneLookupError when the
// name is invalid, the folder does not exist, or holds no such file; the message names the
// scene, the folder and the scenes the folder does hold.
std::string resolveSceneName(const std::string& name, const std::string& scenes_dir);

// Whether a --scene argument names a file (it contains '/' or ends in .yaml or .yml) rather than a
// scene name.
bool isScenePath(const std::string& scene_or_path);

// What a user gave to --scene: a path (it contains '/' or ends in .yaml or .yml) must name an
// existing file and is returned as is; anything else is a scene name, resolved in scenes_dir
// (--scenes-dir) by resolveSceneName. Throws SceneLookupError.
std::string resolveSceneArgument(const std::string& scene_or_path, const std::string& scenes_dir);

}  // namespace thx::scene
