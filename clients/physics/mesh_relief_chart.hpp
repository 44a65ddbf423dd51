#pragma once
// A relief-textured static mesh as a box (textured or not), capsule or cylinder meets it (issue 29,
// "Textured objects" on a curved surface, and plain objects as on the relief plane): the mesh's
// tangent plane at the foot of the object's centre on the smooth surface, with the texture laid on
// it at that face's scale (as hapticd's chart lays it for the pen, server/textured_mesh_renderer.cpp),
// and the smooth surface's bend under it (ground_bend.hpp). On that chart the contacts come from the
// relief plane's rules (relief_raster.hpp, relief_collision.hpp), the ground raised by the bend; for
// a textured box, from both reliefs: Otaduy et al.'s directional depth along the chart's normal.
// Bullet's own box-triangle points are not used: they sit at the box's corners and edges, and a
// point lying in one of the box's grooves does not touch the mesh at all (docs/physics.md,
// "Textured objects"). One chart holds one smooth surface: where an object reaches across a
// crease of the mesh (a rim, a box's edge) the chart stops at the crease, and the faces beyond it
// are met as Bullet's triangles (chart_boundary.hpp).
//
// Only the side the mesh's winding faces is textured (a closed bowl's inside, a sphere's outside):
// an object behind the winding gets no contacts from the chart.
#include <BulletCollision/CollisionShapes/btCollisionShape.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

#include "clients/physics/ground_bend.hpp"
#include "clients/physics/mesh_contact.hpp"
#include "textures/sampling.hpp"
#include "textures/texture_map.hpp"
#include "textures/textured_surface.hpp"

namespace thx::phys {

// What the chart needs of a mesh; attached to its Bullet shape (attachMeshRelief).
struct MeshRelief {
  explicit MeshRelief(const mesh::TexturedMesh& m) : mesh(m) {}
  ContactMesh mesh;
  const tex::TextureMap* map = nullptr;  // a relief map; must outlive the shape
  tex::SampleOptions sampling;
  // The tile (metres per uv) the map's normals were made for (MeshContactOptions::normals_made_for_m).
  Eigen::Vector2d normals_made_for_m = Eigen::Vector2d::Zero();
};

// Attaches `relief` (which must outlive the shape) to a btBvhTriangleMeshShape built from its mesh.
void attachMeshRelief(btCollisionShape& mesh_shape, const MeshRelief& relief);
// The relief attached to a mesh shape; nullptr for any other shape.
const MeshRelief* meshReliefOf(const btCollisionShape& shape);

struct MeshChart {
  tex::TexturedSurface surface;  // its plane frame is the chart, placed in the mesh's frame
  GroundBend bend;               // the smooth surface's height above the chart (chart frame)
  std::uint32_t triangle = 0;    // the foot's triangle
};

// The chart under the point c (mesh frame) of an object reaching `reach_m` from it, starting the
// walk at `triangle` (updated to the foot's; kNoNeighbour: from the nearest triangle, found by
// looking at every one). False where c lies behind the mesh's winding.
bool chartUnder(const MeshRelief& relief, const Eigen::Vector3d& c, double reach_m, std::uint32_t& triangle, MeshChart& out);

// The triangle under a point on the smooth surface near the foot's triangle (for the contact's
// place, as Bullet reports a triangle for its own points).
std::uint32_t triangleUnder(const MeshRelief& relief, const Eigen::Vector3d& p, std::uint32_t from);

}  // namespace thx::phys
