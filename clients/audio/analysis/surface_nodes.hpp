#pragma once
// A tetrahedral mesh's surface as its nodes see it: the boundary faces (corner triangles of
// exactly one tet, oriented away from its fourth corner) and, at every node on them (a corner or,
// for Tet10, an edge midpoint of a boundary face), the outward normal summed over its faces with
// their areas as weights. The listener picks its pickups from them (observation.hpp); the pen's
// scrape on a mesh strikes them along that normal (synthesis/scrape_sites.hpp).
#include <Eigen/Core>
#include <vector>

#include "clients/audio/analysis/tet_mesh.hpp"

namespace thx::audio {

struct SurfaceNodes {
  std::vector<char> on_surface;         // per node
  std::vector<Eigen::Vector3d> normal;  // per node: outward, |n| = twice its faces' area (0 off the surface)
  double area = 0.0;                    // of the boundary faces' corner triangles, m^2
};

SurfaceNodes surfaceNodes(const TetMesh& mesh);

}  // namespace thx::audio
