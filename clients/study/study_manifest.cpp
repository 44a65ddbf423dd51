#include "clients/study/study_manifest.hpp"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <set>

namespace thx::study {
namespace {

namespace fs = std::filesystem;

struct Reader {
  std::string file;

  [[noreturn]] void fail(const YAML::Node& at, const std::string& field, const std::string& problem) const {
    const YAML::Mark m = at.Mark();
    const std::string line = m.line >= 0 ? ":" + std::to_string(m.line + 1) : "";
    throw SessionError(file + line + ": " + field + ": " + problem);
  }

  std::string scalar(const YAML::Node& map, const std::string& key, const std::string& field) const {
    const YAML::Node v = map[key];
    if (!v) fail(map, field, "missing; expected a value");
    if (!v.IsScalar()) fail(v, field, "expected a plain value, got a " + std::string(v.IsMap() ? "mapping" : "sequence"));
    return v.Scalar();
  }

  std::string token(const YAML::Node& map, const std::string& key, const std::string& field) const {
    const std::string s = scalar(map, key, field);
    if (!isToken(s)) fail(map[key], field, "expected a name of letters, digits and _-.+, got '" + s + "'");
    return s;
  }

  // A scene file in the manifest's folder; returns its path.
  std::string sceneFile(const YAML::Node& map, const std::string& key, const std::string& field,
                        const fs::path& dir) const {
    const std::string s = scalar(map, key, field);
    const fs::path p(s);
    if (p.has_parent_path() || p.extension() != ".yaml" || !isToken(p.stem().string()))
      fail(map[key], field,
           "expected a file name NAME.yaml in the manifest's folder (hapticd switches scenes by name "
           "within one folder), got '" + s + "'");
    const fs::path full = dir / p;
    if (!fs::is_regular_file(full)) fail(map[key], field, "no such file: " + full.string());
    return full.string();
  }

  void onlyKeys(const YAML::Node& map, const std::set<std::string>& keys, const std::string& where) const {
    for (const auto& kv : map) {
      const std::string k = kv.first.as<std::string>();
      if (!keys.count(k)) {
        std::string list;
        for (const auto& x : keys) list += (list.empty() ? "" : ", ") + x;
        fail(kv.first, where.empty() ? k : where + "." + k, "unknown field; expected one of " + list);
      }
    }
  }
};

}  // namespace

std::string sceneNameOf(const std::string& scene_path) { return fs::path(scene_path).stem().string(); }

SessionHeader sessionHeaderFor(const StudyManifest& m, const std::string& participant, std::uint64_t seed) {
  SessionHeader h;
  h.study = m.study;
  h.participant = participant;
  h.seed = seed;
  h.software = softwareVersion();
  h.surfaces = m.candidates();
  h.extra.push_back({"manifest", m.source});
  return h;
}

std::vector<Candidate> StudyManifest::candidates() const {
  std::vector<Candidate> out;
  for (const auto& s : surfaces) out.push_back({s.name, s.family});
  return out;
}

StudyManifest loadManifest(const std::string& path) {
  Reader r{path};
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw SessionError(path + ": cannot read the manifest");
  } catch (const YAML::Exception& e) {
    throw SessionError(path + ":" + std::to_string(e.mark.line + 1) + ": not valid YAML: " + e.msg);
  }
  if (!root.IsMap()) throw SessionError(path + ": expected a mapping with study and surfaces");

  StudyManifest m;
  m.source = path;
  const fs::path dir = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
  m.dir = dir.string();
  const std::string study = r.scalar(root, "study", "study");
  const auto s = parseStudy(study);
  if (!s) r.fail(root["study"], "study", "expected identification or relief-vs-normal, got '" + study + "'");
  m.study = *s;
  const bool ident = m.study == Study::Identification;
  r.onlyKeys(root, ident ? std::set<std::string>{"study", "training", "surfaces"} : std::set<std::string>{"study", "surfaces"}, "");
  if (ident) m.training = r.sceneFile(root, "training", "training", dir);

  const YAML::Node list = root["surfaces"];
  if (!list) r.fail(root, "surfaces", "missing; expected a list of surfaces");
  if (!list.IsSequence()) r.fail(list, "surfaces", "expected a list of surfaces");
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node e = list[i];
    const std::string f = "surfaces[" + std::to_string(i) + "]";
    if (!e.IsMap()) r.fail(e, f, "expected a mapping {name, family, ...}");
    r.onlyKeys(e, ident ? std::set<std::string>{"name", "family", "scene"} : std::set<std::string>{"name", "family", "relief", "normal"}, f);
    ManifestSurface ms;
    ms.name = r.token(e, "name", f + ".name");
    if (!names.insert(ms.name).second) r.fail(e["name"], f + ".name", "'" + ms.name + "' is named twice; expected unique names");
    ms.family = r.token(e, "family", f + ".family");
    if (ident) {
      ms.scene = r.sceneFile(e, "scene", f + ".scene", dir);
    } else {
      ms.relief = r.sceneFile(e, "relief", f + ".relief", dir);
      ms.normal = r.sceneFile(e, "normal", f + ".normal", dir);
      if (ms.relief == ms.normal) r.fail(e["normal"], f + ".normal", "the same file as relief; expected the surface's normal-map scene");
    }
    m.surfaces.push_back(std::move(ms));
  }
  const std::size_t n = m.surfaces.size();
  if (ident && n < 2) r.fail(list, "surfaces", "expected at least 2 candidates, got " + std::to_string(n));
  if (!ident && (n < 2 || n % 2 != 0))
    r.fail(list, "surfaces", "expected an even number (at least 2) so half can be relief and half normal, got " + std::to_string(n));
  return m;
}

}  // namespace thx::study
