#include "clients/visual/mesh_surface.hpp"

#include <string>

#include "base/error.hpp"

namespace thx::visual {

void checkMeshSurface(const MeshSurface& s) {
  const auto fail = [](const std::string& what) { throw Error(Error::Kind::Config, "textured mesh: " + what); };
  if (s.mesh == nullptr) fail("no mesh");
  if (!s.mesh->hasFrames() || s.mesh->triangles.empty())
    fail(s.mesh->source + ": no triangles with vertex frames (buildVertexFrames not run?)");
  if (s.map == nullptr) fail(s.mesh->source + ": no texture");
  if (!(s.tile_m.allFinite() && s.tile_m.minCoeff() > 0.0))
    fail(s.mesh->source + ": tile " + std::to_string(s.tile_m.x()) + " x " + std::to_string(s.tile_m.y()) +
         " m; expected > 0");
}

}  // namespace thx::visual
