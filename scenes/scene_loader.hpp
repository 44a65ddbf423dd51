#pragma once
// Reading scene files (format: docs/scenes.md). Every problem throws SceneError naming the file,
// line, column, field path, offending value and what was expected; non-fatal issues land in
// Scene::warnings. Texture files and script path files are checked to exist, and generator
// kinds and parameters are checked against the textures library's registry, at load time.
#include <string>

#include "scenes/scene.hpp"
#include "scenes/scene_error.hpp"

namespace thx::scene {

// Reads and validates a scene file; relative paths inside resolve against its directory.
Scene loadScene(const std::string& path);

// Same from text: `source_name` is what messages call it, `base_dir` resolves relative paths
// ("" = the current directory). Text above 1 MiB is refused as not a scene (loadScene checks the
// file's size before reading it).
Scene parseScene(const std::string& yaml_text, const std::string& source_name, const std::string& base_dir);

// For the code that hears the plane only (the audio libraries without a mesh's tetrahedra): throws
// SceneError at the scene's `mesh:` if its surface is a mesh, naming `program` and what to run
// instead. Textured meshes are felt (hapticd), simulated (physics-client), drawn (visual-client)
// and sounded (the audio-client program, which links Gmsh).
void requirePlaneSurface(const Scene& scene, const std::string& program);

}  // namespace thx::scene
