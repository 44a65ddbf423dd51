#pragma once
// Built-in textured meshes: sphere, cylinder, torus, box and surfaces of revolution (lathe: a bowl,
// a vase), with texture coordinates at a stated physical scale and their vertex frames built
// (textured_mesh.hpp). Every generator's uv is arc length / tile_m along each direction; around a
// closed loop the tile is adjusted to the nearest whole number of tiles so the wrapped texture
// meets itself at the seam (the tile used is returned in `tile_used_m`). Generated meshes are
// closed where the shape is (sphere, torus, box; a lathe whose profile starts and ends on the
// axis) and wound counter-clockwise seen from outside.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "meshes/textured_mesh.hpp"

namespace thx::mesh {

struct GeneratedMesh {
  TexturedMesh mesh;
  Eigen::Vector2d tile_used_m{0.0, 0.0};  // metres per uv unit along u and v
};

// UV sphere about the origin: `segments` around z, `rings` from pole to pole. u runs east around
// z, v from the south pole (-z) to the north pole.
GeneratedMesh sphere(double radius_m, int segments, int rings, double tile_m);

// Open tube about the z axis from z = 0 to height_m, normals outward (inward: the inside of a
// pipe); u around, v along z.
GeneratedMesh cylinder(double radius_m, double height_m, int segments, int rows, double tile_m, bool inward = false);

// Torus about the z axis: major radius R (centre of the tube), minor radius r.
GeneratedMesh torus(double major_radius_m, double minor_radius_m, int segments, int rings, double tile_m);

// Axis-aligned box centred at the origin, each face split into n x n quads (n from `cells_per_m`,
// at least 1). inward: the normals point into the box (its inside is the surface: a room's inside
// corners).
GeneratedMesh box(const Eigen::Vector3d& size_m, double cell_m, double tile_m, bool inward = false);

// A surface of revolution about z: the profile (r >= 0, z) in order, swept `segments` times
// around. The outward normal is on the right of the profile's direction in the (r, z) half-plane:
// a profile that rises on the outside of a shape and comes down its inside makes a closed shell.
// Points on the axis (r == 0) close the surface there. u around, v along the profile's arc length.
GeneratedMesh lathe(const std::vector<Eigen::Vector2d>& profile, int segments, double tile_m);

// Profiles of the shipped shapes (for lathe): a bowl with a rounded rim and a wall of
// `wall_m`, and a vase; both start and end on the axis (closed shells).
std::vector<Eigen::Vector2d> bowlProfile(double radius_m, double height_m, double wall_m, int samples);
std::vector<Eigen::Vector2d> vaseProfile(double height_m, double max_radius_m, double wall_m, int samples);

}  // namespace thx::mesh
