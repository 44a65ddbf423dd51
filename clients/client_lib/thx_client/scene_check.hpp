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
#include "scenes/scene_lookup.hpp"
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

// ---- Finding a scene file: scenes/scene_lookup.hpp, here for clients ----------------------------

using scene::isScenePath;
using scene::isValidSceneName;
using scene::requireValidSceneName;
using scene::resolveSceneArgument;
using scene::resolveSceneName;  // use it for hello_t.scene_name
using scene::SceneLookupError;

}  // namespace thx::client
