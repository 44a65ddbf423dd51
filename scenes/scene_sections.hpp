#pragma once
// The loader's section parsers (internal to thx_scenes). Each takes the Field of its section and
// what it must agree with, validates every value and fills every default.
#include <optional>
#include <vector>

#include "scenes/scene.hpp"
#include "scenes/yaml_field.hpp"

namespace thx::scene::detail {

Pose parsePose(const Field& field);
// A name from the materials table or the scene's own materials, or {name, rolling_friction}.
Material parseMaterial(const Field& field);
// The top-level `materials:` sequence: materials defined by the scene, beside the table's.
std::vector<Material> parseCustomMaterials(const std::optional<Field>& field);
// device.pen (clients/audio: the pen's own modes).
Pen parsePen(const Field& field);
// A file that must exist when the scene is loaded; returns the resolved path.
std::string parseExistingFile(const Field& field, const std::string& what);

Rates parseRates(const std::optional<Field>& field);
Audio parseAudio(const std::optional<Field>& field);
Surface parseSurface(const Field& field);
tex::GenerateRequest parseGenerator(const Field& texture, const Surface& surface);
// Script positions are checked against the surface, forces against the device model.
Device parseDevice(const std::optional<Field>& field, const Surface& surface);
std::vector<ScriptStep> parseScript(const Field& field, const Surface& surface, const DeviceModel& model);
std::vector<SceneObject> parseObjects(const std::optional<Field>& field, const Surface& surface);

// Checks between sections that are not errors but likely mistakes; they become warnings at the
// most specific field present.
void warnAboutInconsistencies(const Field& root, const Scene& scene);

}  // namespace thx::scene::detail
