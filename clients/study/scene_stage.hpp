#pragma once
// The scene folder a real session runs on (docs/study.md §7): every scene of a manifest, and for
// Study 1 each surface's cue-removed variants, written into one folder that hapticd
// (--scenes-dir) and the clients follow switches in:
//   NAME.yaml         the manifest's scene (relative file paths made absolute)
//   NAME.nopen.yaml   the same with device.stiffness_fraction and damping 0: hapticd renders no force, the
//                     pen still moves the cursor ("no pen")
//   NAME.noball.yaml  the same without objects: the physics client rolls nothing ("no ball")
//   NAME.nosound.yaml the same with audio.mute: the audio client plays exact silence ("no sound")
// A switch keeps the device and the servo rate, so the variants change nothing else.
#include <string>
#include <vector>

#include "clients/study/session.hpp"
#include "clients/study/study_manifest.hpp"

namespace thx::study {

// The name hapticd is switched to for a trial of `scene_path` under `cues` (Study 1 removes at
// most one cue): "bricks", "bricks.nopen", "bricks.noball", "bricks.nosound".
std::string stagedSceneName(const std::string& scene_path, const Cues& cues);

// Writes the folder (created if missing; existing files of these names are replaced). Returns
// the files written. Throws SessionError naming a scene that cannot be read or rewritten.
std::vector<std::string> stageScenes(const StudyManifest& m, const std::string& dir);

}  // namespace thx::study
