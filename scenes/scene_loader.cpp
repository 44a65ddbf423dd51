#include "scenes/scene_loader.hpp"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "scenes/scene_sections.hpp"

namespace thx::scene {

namespace {

constexpr int kFormatVersion = 1;
// A scene is a page of YAML; anything this large is the wrong file.
constexpr std::uintmax_t kMaxSceneBytes = 1 << 20;

YAML::Node parseYaml(const std::string& text, const std::string& source) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    const SourceLocation where =
        e.mark.is_null() ? SourceLocation{source, 0, 0} : SourceLocation{source, e.mark.line + 1, e.mark.column + 1};
    throw SceneError(where, "", "YAML syntax error: " + e.msg, "well-formed YAML (spaces, not tabs, for indentation)");
  }
}

Scene parseRoot(const Field& root, const std::string& source, const std::string& base_dir,
                std::vector<Material>& custom_materials) {
  const std::string top =
      "a mapping with version, name, surface and optionally description, device or devices, objects, rates, audio, "
      "materials";
  if (root.isNull()) root.fail("empty scene", top, "");
  root.expectKeys(
      {"version", "name", "description", "surface", "device", "devices", "objects", "rates", "audio", "materials"});

  Scene scene;
  scene.source = source;
  scene.base_dir = base_dir;
  const Field version =
      root.at("version", "version: " + std::to_string(kFormatVersion) + " (the scene format version)");
  if (version.integer(0, 1000000) != kFormatVersion)
    version.fail("unsupported version", std::to_string(kFormatVersion) + " (the only format this loader reads)");
  scene.name = root.at("name", "a non-empty scene name").text();
  if (auto d = root.find("description")) scene.description = d->text();
  scene.rates = detail::parseRates(root.find("rates"));
  scene.audio = detail::parseAudio(root.find("audio"));
  // Before every section that may name one of them.
  custom_materials = detail::parseCustomMaterials(root.find("materials"));
  scene.custom_materials = custom_materials;
  scene.surface = detail::parseSurface(root.at("surface", "a mapping with at least size and texture"));
  if (const auto list = root.find("devices")) {
    if (root.has("device"))
      list->fail("both `device` and `devices`", "one of them: `device:` for one device, `devices:` for a list", "");
    std::vector<Device> devices = detail::parseDevices(*list, scene.surface);
    scene.device = devices.front();
    scene.other_devices.assign(devices.begin() + 1, devices.end());
  } else {
    scene.device = detail::parseDevice(root.find("device"), scene.surface);
  }
  scene.objects = detail::parseObjects(root.find("objects"), scene.surface);
  return scene;
}

}  // namespace

Scene parseScene(const std::string& yaml_text, const std::string& source_name, const std::string& base_dir) {
  if (yaml_text.size() > kMaxSceneBytes)
    throw SceneError({source_name, 0, 0}, "", "text too large for a scene",
                     "at most " + std::to_string(kMaxSceneBytes) + " bytes", std::to_string(yaml_text.size()) + " bytes");
  std::vector<std::string> warnings;
  std::vector<Material> custom_materials;
  const ParseContext context{source_name, base_dir, &warnings, &custom_materials};
  const YAML::Node document = parseYaml(yaml_text, source_name);
  const Field root = Field::root(context, document);
  Scene scene = parseRoot(root, source_name, base_dir, custom_materials);
  detail::warnAboutInconsistencies(root, scene);
  scene.warnings = std::move(warnings);
  return scene;
}

Scene loadScene(const std::string& path) {
  const SourceLocation file{path, 0, 0};
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status))
    throw SceneError(file, "", "scene file not found", "an existing YAML scene file");
  if (!std::filesystem::is_regular_file(status)) throw SceneError(file, "", "not a regular file", "a YAML scene file");
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (!ec && bytes > kMaxSceneBytes)
    throw SceneError(file, "", "file too large for a scene", "at most " + std::to_string(kMaxSceneBytes) + " bytes",
                     std::to_string(bytes) + " bytes");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(file, "", "cannot open scene file", "a readable YAML scene file");
  std::ostringstream text;
  text << in.rdbuf();
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return parseScene(text.str(), path, dir.empty() ? std::string(".") : dir);
}

void requirePlaneSurface(const Scene& scene, const std::string& program) {
  if (!scene.surface.mesh) return;
  throw SceneError(scene.surface.mesh->where, "surface.mesh",
                   program + " sounds a textured plane only; a mesh surface is felt by hapticd, simulated by "
                             "physics-client, drawn by visual-client and sounded by the audio-client program (live and "
                             "offline), which fills the mesh with tetrahedra (Gmsh)",
                   "a scene without surface.mesh");
}

}  // namespace thx::scene
