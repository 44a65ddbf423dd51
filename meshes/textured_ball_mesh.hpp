#pragma once
// A ball whose surface carries one texture (issue 29, "a sphere with a bump map"), laid out as a
// cube projected onto the sphere, each of the six faces an equi-angular chart: the box's layout
// (textured_box_mesh.hpp) carried onto the ball. The physics reads its bump map through
// ballChartAt (clients/physics/textured_ball.hpp); the visual client draws texturedBallMesh.
//
// Layout: a direction w from the centre belongs to the face of the axis a along which |w_a| is
// largest (its outward normal sign(w_a) e_a). On it, u grows along e_(a+1) and v along e_(a+2)
// (axes mod 3), measured in metres along the great circles through the face's centre:
// u = r atan(w_(a+1) / |w_a|), v = r atan(w_(a+2) / |w_a|), zero at the face's centre and
// +-r pi/4 at its edges (equi-angular: a texel's area on the ball varies less over a face than in
// the plain cube projection). So at the face's centre the texture lies at its stated scale, and
// the negative faces are mirrored charts (handedness -1), as on the box.
// Across a face's edge the texture continues only if it is symmetric under swapping u and v and
// one face spans a whole number of tiles (the default tile, r pi/2, is exactly one face): face A
// reads T(+-1/2, t) where face B reads T(t, +-1/2).
#include <Eigen/Core>

#include "meshes/textured_mesh.hpp"

namespace thx::mesh {

// The chart at a direction from the ball's centre.
struct BallChartPoint {
  int axis = 2;          // the face's axis a
  double sign = 1.0;     // its outward normal is sign * e_a
  Eigen::Vector2d uv_m = Eigen::Vector2d::Zero();  // metres on the ball, zero at the face's centre
  // The surface gradients of u and v (per metre of the ball's surface, tangent to it): unit and
  // along e_(a+1), e_(a+2) at the face's centre, longer and sheared towards its corners. A depth
  // d(u, v) recessed into the ball tilts its normal to N + d_u du + d_v dv.
  Eigen::Vector3d du = Eigen::Vector3d::UnitX();
  Eigen::Vector3d dv = Eigen::Vector3d::UnitY();
};

// `direction` need not be unit, and must not be zero; radius_m > 0.
BallChartPoint ballChartAt(const Eigen::Vector3d& direction, double radius_m);
// Its face and uv alone (du and dv left at their defaults), at a direction already made unit as
// ballChartAt makes it (direction.normalized()): the same to the bit. For reads of the depth alone,
// which a ball's contacts make at every texel under it.
BallChartPoint ballChartUvAtUnit(const Eigen::Vector3d& unit_direction, double radius_m);

// The face a tile spans exactly once: its edge's arc, r pi / 2.
double ballFaceArc(double radius_m);

// Centred on the origin; each face a grid of cells x cells quads (two triangles each), its vertices
// on the sphere at equal angles; uv counts tiles; frames by buildVertexFrames (smooth normals
// everywhere, tangents split at the faces' seams). Throws thx::Error (Config) for a radius or tile
// that is not positive and finite, or cells outside [1, 256].
TexturedMesh texturedBallMesh(double radius_m, double tile_m, int cells = 24);

}  // namespace thx::mesh
