#pragma once
// What the command handler (server_commands.hpp) needs of whoever loads scenes for a switch:
// start a load, and later learn how it ended. hapticd's is SceneSwitcher (scene_switcher.hpp);
// tests pass a fake. Called from the publisher thread only.
#include <cstdint>
#include <optional>
#include <string>

namespace thx::srv {

class SceneLoads {
 public:
  struct Outcome {
    bool ok = false;
    std::string error;              // when !ok: the loader's message (file:line for scene errors)
    std::uint32_t swap = 0;         // when ok: TickRecord::scene_swaps once the servo renders it
    std::string scene_name;         // when ok: scene::sceneName, for hello_t
    std::uint64_t fingerprint = 0;  // when ok: the surface's texture fingerprint, for hello_t
  };

  virtual ~SceneLoads() = default;
  // Starts loading scene `name` off the calling thread; the reason when it cannot start now.
  virtual std::optional<std::string> begin(const std::string& name) = 0;
  // How the load begun last ended, once: failed, or handed to the servo (which applies it at a
  // tick boundary after its ramp down). Nothing while it is still loading or nothing was begun.
  virtual std::optional<Outcome> poll() = 0;
};

}  // namespace thx::srv
