#include "clients/study/scene_stage.hpp"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>

namespace thx::study {
namespace {

namespace fs = std::filesystem;

// A relative path in a scene is relative to the scene's folder; the staged copy lives elsewhere.
void absolutise(YAML::Node node, const fs::path& base) {
  if (!node || !node.IsScalar()) return;
  const fs::path p(node.Scalar());
  if (p.is_relative()) node = fs::absolute(base / p).lexically_normal().string();
}

void write(const YAML::Node& root, const fs::path& file, std::vector<std::string>& written) {
  YAML::Emitter e;
  e << root;
  std::ofstream out(file);
  out << "# Staged by study-run --stage (docs/study.md §7): do not edit, run the stage again.\n" << e.c_str() << "\n";
  if (!out) throw SessionError(file.string() + ": cannot write the staged scene");
  written.push_back(file.string());
}

void stageOne(const std::string& scene_path, bool variants, const fs::path& dir, std::vector<std::string>& written) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(scene_path);
  } catch (const YAML::Exception& e) {
    throw SessionError(scene_path + ": cannot stage the scene: " + e.what());
  }
  const fs::path base = fs::path(scene_path).parent_path();
  if (root["surface"] && root["surface"]["texture"]) absolutise(root["surface"]["texture"]["file"], base);
  if (root["device"] && root["device"]["script"] && root["device"]["script"].IsSequence())
    for (YAML::Node step : root["device"]["script"]) absolutise(step["path_file"], base);
  const std::string name = sceneNameOf(scene_path);
  write(root, dir / (name + ".yaml"), written);
  if (!variants) return;
  YAML::Node no_pen = YAML::Clone(root);
  no_pen["device"]["stiffness_fraction"] = 0.0;  // no spring,
  no_pen["device"]["damping"] = 0.0;             // no virtual damping either
  write(no_pen, dir / (name + ".nopen.yaml"), written);
  YAML::Node no_ball = YAML::Clone(root);
  no_ball.remove("objects");
  write(no_ball, dir / (name + ".noball.yaml"), written);
  YAML::Node no_sound = YAML::Clone(root);
  no_sound["audio"]["mute"] = true;  // the audio client plays exact silence (docs/scenes.md, audio)
  write(no_sound, dir / (name + ".nosound.yaml"), written);
}

}  // namespace

std::string stagedSceneName(const std::string& scene_path, const Cues& cues) {
  const std::string name = sceneNameOf(scene_path);
  if (!cues.pen) return name + ".nopen";
  if (!cues.ball) return name + ".noball";
  if (!cues.sound) return name + ".nosound";
  return name;
}

std::vector<std::string> stageScenes(const StudyManifest& m, const std::string& dir) {
  fs::create_directories(dir);
  std::vector<std::string> written;
  if (m.training) stageOne(*m.training, false, dir, written);
  for (const ManifestSurface& s : m.surfaces) {
    if (m.study == Study::Identification) {
      stageOne(s.scene, true, dir, written);
    } else {
      stageOne(s.relief, false, dir, written);
      stageOne(s.normal, false, dir, written);
    }
  }
  return written;
}

}  // namespace thx::study
