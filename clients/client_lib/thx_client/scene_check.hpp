#pragma once
// Does this client run the scene hapticd runs? hello_t names the server's scene (scene_name: the
// scene file's stem) and the fingerprint of its textured surface (texture_fingerprint); a client
// compares them with its own before it feels, simulates, plays or shows anything
// (docs/clients.md, "Same scene"). And: where is the scene file of a name, on this host.
//
// The client side of thx::scene::sceneName() and scene::SceneSurface::fingerprint
// (scenes/scene_surface.hpp). Fingerprints print as tex::formatFingerprint does (0x + 16 hex digits).
#include <cstdint>
#include <stdexcept>
#include <string>

#include "base/error.hpp"
#include "thx_msgs/hello_t.hpp"

namespace thx::client {

// A scene as the wire names it.
struct SceneIdentity {
  std::string name;                       // the scene file's stem, e.g. "marble_bricks"
  std::uint64_t texture_fingerprint = 0;  // scene::SceneSurface::fingerprint
  bool operator==(const SceneIdentity&) const = default;
};

// The server's scene, from its hello.
SceneIdentity sceneOf(const thx_msgs::hello_t& hello);

enum class SceneVerdict {
  Same,            // same name and same fingerprint
  Differs,         // an error: the client must stop
  DiffersAllowed,  // different, but the client was told to differ: a warning
};

struct SceneCheck {
  SceneVerdict verdict = SceneVerdict::Same;
  // "" when Same; otherwise one line naming both scenes and both fingerprints (and, for Differs,
  // how to fix it or to differ on purpose with --allow-different-scene).
  std::string message;
  bool ok() const { return verdict != SceneVerdict::Differs; }
};

// Compares the server's scene (from its hello) with the client's own. Any difference of name or
// fingerprint differs: another scene, or the same name with another texture (the two hosts'
// scenes folders hold different files, or a texture file changed). With allow_different_scene
// a difference is reported as a warning (the material-identification study shows other looks on
// purpose) and ok() stays true.
SceneCheck checkScene(const thx_msgs::hello_t& hello, const SceneIdentity& mine, bool allow_different_scene);
SceneCheck checkScene(const SceneIdentity& server, const SceneIdentity& mine, bool allow_different_scene,
                      const std::string& server_label = "hapticd");

// ---- Finding a scene file -------------------------------------------------------------------

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
// scene, the folder and the scenes the folder does hold. Use it for hello_t.scene_name.
std::string resolveSceneName(const std::string& name, const std::string& scenes_dir);

// Whether a --scene argument names a file (it contains '/' or ends in .yaml or .yml) rather than a
// scene name.
bool isScenePath(const std::string& scene_or_path);

// What a user gave to --scene: a path (it contains '/' or ends in .yaml or .yml) must name an
// existing file and is returned as is; anything else is a scene name, resolved in scenes_dir
// (--scenes-dir) by resolveSceneName. Throws SceneLookupError.
std::string resolveSceneArgument(const std::string& scene_or_path, const std::string& scenes_dir);

}  // namespace thx::client
