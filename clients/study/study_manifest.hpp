#pragma once
// A study's manifest (docs/study.md §5.1): which study, the candidate surfaces with their sound
// families and their scene files, and Study 1's training scene. The trial runner reads it; the
// shipped ones are scenes/study/identification.yaml and scenes/study/relief_vs_normal.yaml.
//
// Scene files are plain file names in the manifest's folder: hapticd switches scenes by name
// within one folder (--scenes-dir), so the runner starts hapticd on that folder.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "clients/study/session.hpp"

namespace thx::study {

struct ManifestSurface {
  std::string name, family;
  std::string scene;   // Study 1: the scene file (path: manifest folder / file)
  std::string relief;  // Study 2: the surface shown as a relief map
  std::string normal;  // Study 2: the same surface as a normal map
};

struct StudyManifest {
  std::string source;  // the manifest file, for messages
  std::string dir;     // its folder: the scenes live here
  Study study = Study::Identification;
  std::optional<std::string> training;  // Study 1: the training scene's path
  std::vector<ManifestSurface> surfaces;

  std::vector<Candidate> candidates() const;
};

// Reads and checks a manifest. Throws SessionError naming file, line, field, what was expected
// and what was found, e.g. "m.yaml:4: surfaces[1].family: expected a name of letters, digits
// and _-.+, got 'tile wall'". Scene files must exist.
StudyManifest loadManifest(const std::string& path);

// A session's header for this manifest: study, participant, seed, this build's version, the
// candidates, and an extra line naming the manifest.
SessionHeader sessionHeaderFor(const StudyManifest& m, const std::string& participant, std::uint64_t seed);

// The scene name hapticd knows a scene file by (its stem): ".../bricks_red.yaml" -> "bricks_red".
std::string sceneNameOf(const std::string& scene_path);

}  // namespace thx::study
