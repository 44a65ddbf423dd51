#pragma once
// A box whose six faces carry one texture, laid out as a textured object's faces are
// (clients/physics/textured_box.hpp, issue 29): the texture spans `tile_m` on each face; on the
// face whose outward normal is ±e_a, u grows along e_(a+1) and v along e_(a+2) (axes mod 3), both
// zero at the face's centre. So the tangent frame of a face is (e_(a+1), e_(a+2), ±e_a): mirrored
// (handedness -1) on the three negative faces, which is how the physics reads the map there too.
// The visual client draws a textured box from this mesh; the physics reads the same layout.
#include <Eigen/Core>

#include "meshes/textured_mesh.hpp"

namespace thx::mesh {

// Centred on the origin, edges `size_m` (full lengths, each > 0) along the axes, two triangles a
// face, with frames (hard edges). uv counts tiles. Throws thx::Error (Config) for a size or tile
// that is not positive and finite.
TexturedMesh texturedBoxMesh(const Eigen::Vector3d& size_m, double tile_m);

}  // namespace thx::mesh
