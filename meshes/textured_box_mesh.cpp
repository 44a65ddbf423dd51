#include "meshes/textured_box_mesh.hpp"

#include <cmath>

#include "base/error.hpp"

namespace thx::mesh {

TexturedMesh texturedBoxMesh(const Eigen::Vector3d& size_m, double tile_m) {
  if (!size_m.allFinite() || (size_m.array() <= 0.0).any() || !std::isfinite(tile_m) || tile_m <= 0.0)
    throw Error(Error::Kind::Config, "textured box: edges and texture tile must be positive and finite");
  TexturedMesh box;
  box.source = "textured box";
  const Eigen::Vector3d half = 0.5 * size_m;
  for (int a = 0; a < 3; ++a) {
    const int ua = (a + 1) % 3, va = (a + 2) % 3;
    for (const double sign : {1.0, -1.0}) {
      const auto first = std::uint32_t(box.positions.size());
      for (const auto& [su, sv] : {std::pair{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}}) {
        Eigen::Vector3d p = Eigen::Vector3d::Zero();
        p[a] = sign * half[a];
        p[ua] = su * half[ua];
        p[va] = sv * half[va];
        box.positions.push_back(p);
        box.uvs.emplace_back(p[ua] / tile_m, p[va] / tile_m);
      }
      // Counter-clockwise seen from outside: e_ua x e_va = e_a, so the order above winds outwards
      // on the positive face and must be reversed on the negative one.
      if (sign > 0.0) {
        box.triangles.push_back({first, first + 1, first + 2});
        box.triangles.push_back({first, first + 2, first + 3});
      } else {
        box.triangles.push_back({first, first + 2, first + 1});
        box.triangles.push_back({first, first + 3, first + 2});
      }
    }
  }
  buildVertexFrames(box);
  return box;
}

}  // namespace thx::mesh
