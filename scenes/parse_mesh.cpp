// surface.mesh: the surface as a textured triangle mesh, from a built-in shape or a mesh file.
#include <sstream>

#include "meshes/builtin_shapes.hpp"
#include "scenes/scene_sections.hpp"

namespace thx::scene::detail {

namespace {

// A mesh file or shape larger than this is not a surface a pen can reach.
constexpr double kMaxShapeSizeM = 1.0;
// A bound the scene may raise, up to what the renderer's hierarchy was measured at (docs/meshes.md).
constexpr long long kMaxTrianglesLimit = 4'000'000;

std::vector<std::pair<std::string, std::string>> shapeChoices() {
  std::vector<std::pair<std::string, std::string>> choices;
  std::istringstream names(mesh::kBuiltInShapes);
  for (std::string name; std::getline(names, name, '|');) choices.emplace_back(name, name);
  return choices;
}

}  // namespace

MeshSource parseMesh(const Field& field, const Surface& surface) {
  const FileOrGenerator given = parseFileOrGenerator(
      field, {"generator", "size", "segments", "file", "unit", "projection", "max_triangles", "closed", "pose"}, "mesh",
      "{generator: SHAPE, size: m} or {file: PATH}");
  const auto& file = given.file;
  const auto& generator = given.generator;
  MeshSource m;
  m.where = field.location();
  if (generator) {
    refuseKeys(field, {"unit", "projection"}, "mesh files", "generator:");
    m.kind = MeshSource::Kind::Generator;
    m.generator = generator->choice<std::string>(shapeChoices());
    m.size_m = field.at("size", "the shape's radius in metres").number(positiveUpTo(kMaxShapeSizeM, "m"));
    if (auto s = field.find("segments")) m.segments = int(s->integer(8, 4096, "segments"));
    // A generator lays the texture on square tiles of surface.size.
    if (surface.size_m.x() != surface.size_m.y())
      generator->fail("a generated mesh tiles the texture in squares",
                      "surface.size [s, s] (metres per texture tile)",
                      "[" + formatNumber(surface.size_m.x()) + ", " + formatNumber(surface.size_m.y()) + "]");
  } else {
    refuseKeys(field, {"size", "segments"}, "generated meshes", "file:");
    m.kind = MeshSource::Kind::File;
    m.file = parseExistingFile(*file, "mesh file (OBJ, PLY, glTF 2.0 or STL)");
    if (auto u = field.find("unit")) m.unit_m = u->number(positiveUpTo(1000.0, "m per file unit"));
    if (auto p = field.find("projection"))
      m.projection = p->choice<MeshProjection>({{"none", MeshProjection::None},
                                                {"planar", MeshProjection::Planar},
                                                {"cylindrical", MeshProjection::Cylindrical},
                                                {"spherical", MeshProjection::Spherical}});
  }
  if (auto t = field.find("max_triangles")) m.max_triangles = std::size_t(t->integer(1, kMaxTrianglesLimit, "triangles"));
  if (auto p = field.find("pose")) m.pose = parsePose(*p);
  if (auto c = field.find("closed"))
    m.closed = c->choice<bool>({{"true", true}, {"false", false}});
  return m;
}

}  // namespace thx::scene::detail
