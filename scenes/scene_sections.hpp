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

// A source given by exactly one of `file:` and `generator:` (a texture, a mesh), in a mapping of
// `keys`; `what` names it ("texture", "mesh"), `expected` is the form for a message.
struct FileOrGenerator {
  std::optional<Field> file, generator;
};
FileOrGenerator parseFileOrGenerator(const Field& field, const std::vector<std::string>& keys, const std::string& what,
                                     const std::string& expected);
// The keys of `field` that apply only to the other kind of source are errors: "applies only to
// `only_to`", expected "no 'KEY' with `with`".
void refuseKeys(const Field& field, std::initializer_list<const char*> keys, const std::string& only_to,
                const std::string& with);

Rates parseRates(const std::optional<Field>& field);
Audio parseAudio(const std::optional<Field>& field);
Surface parseSurface(const Field& field);
// surface.mesh; `surface` has its size (a generated mesh tiles the texture in squares of it).
MeshSource parseMesh(const Field& field, const Surface& surface);
// `size_name` names surface.size_m in warnings (an object's texture passes "texture_tile").
tex::GenerateRequest parseGenerator(const Field& texture, const Surface& surface,
                                    const std::string& size_name = "surface.size");
// A texture given by file or generator; a generator's extent defaults to surface.size_m.x().
TextureSource parseTexture(const Field& field, const Surface& surface, const std::string& size_name = "surface.size");
// Script positions are checked against the surface, forces against the device model.
Device parseDevice(const std::optional<Field>& field, const Surface& surface);
// `devices:` (issue 30): one device or more, at most kMaxSceneDevices, names and VRPN addresses
// distinct; each a `device:` section with an optional name (default Phantom<i>).
std::vector<Device> parseDevices(const Field& field, const Surface& surface);
std::vector<ScriptStep> parseScript(const Field& field, const Surface& surface, const DeviceModel& model);
std::vector<SceneObject> parseObjects(const std::optional<Field>& field, const Surface& surface);

// Checks between sections that are not errors but likely mistakes; they become warnings at the
// most specific field present.
void warnAboutInconsistencies(const Field& root, const Scene& scene);

}  // namespace thx::scene::detail
