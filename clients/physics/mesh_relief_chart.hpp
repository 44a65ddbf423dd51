#pragma once
// A relief-textured static mesh as a box (textured or not), capsule, cylinder or ball with a bump
// map meets it (issue 29, "Textured objects" on a curved surface, and plain objects as on the
// relief plane): the mesh's tangent plane at the foot of the object's centre on the smooth
// surface, with the texture laid on it as hapticd's chart lays it for the pen
// (server/textured_mesh_renderer.cpp) but at the scale interpolated from the vertices, and where
// the uv squeezes it, its envelope (relief_envelope.hpp); and the smooth surface's bend under it
// (ground_bend.hpp). On that chart the contacts come from the relief plane's rules
// (relief_raster.hpp, relief_collision.hpp), the ground raised by the bend; for a textured box or
// ball, from both reliefs: Otaduy et al.'s directional depth along the chart's normal.
// Bullet's own box-triangle points are not used: they sit at the box's corners and edges, and a
// point lying in one of the box's grooves does not touch the mesh at all (docs/physics.md,
// "Textured objects"). One chart holds one smooth surface: where an object reaches across a
// crease of the mesh (a rim, a box's edge) the chart stops at the crease, and each surface beyond
// it is met on a chart of its own, cut at the crease the same way (chart_boundary.hpp).
//
// Only the side the mesh's winding faces is textured (a closed bowl's inside, a sphere's outside):
// an object behind the winding gets no contacts from a relief's chart.
//
// A mesh without a relief (untextured, or normal-mapped: a normal map has no depth) has a smooth
// chart: the same tangent plane and bend with nothing laid on it, so that a box, capsule or
// cylinder meets the curved surface the mesh stands for rather than its flat triangles (the ball's
// rule, mesh_contact.hpp, for every shape). Having no texture to lay, its frame is turned to the
// object's own axis and sampled on a grid laid over the object's footprint (layGridUnder): the
// footprint's edges and corners are samples, at a spacing that is a fraction of the object, so
// their number does not grow with the object or the mesh (a textured box's or ball's relief is
// read at its own texels). Both sides of the mesh are met, as Bullet's triangles are (a closed sphere's inside is
// a bowl).
#include <BulletCollision/CollisionShapes/btCollisionShape.h>
#include <BulletCollision/CollisionShapes/btConcaveShape.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <limits>

#include "clients/physics/ground_bend.hpp"
#include "clients/physics/mesh_contact.hpp"
#include "clients/physics/relief_envelope.hpp"
#include "textures/sampling.hpp"
#include "textures/texture_map.hpp"
#include "textures/textured_surface.hpp"

namespace thx::phys {

// A smooth chart's grid intervals along the object's longer side unless a mesh says otherwise.
inline constexpr int kSmoothChartIntervals = 16;

// What the chart needs of a mesh; attached to its Bullet shape (attachMeshRelief).
struct MeshRelief {
  explicit MeshRelief(const mesh::TexturedMesh& m);
  ContactMesh mesh;
  // Per triangle, where it lies from a pole of the uv (poleFans): kPoleFan, kPoleRing or 0.
  std::vector<std::uint8_t> pole;
  const tex::TextureMap* map = nullptr;  // a relief map; must outlive the shape. nullptr: a smooth chart
  // The map's envelopes, for a chart where the uv squeezes it (relief_envelope.hpp); without them
  // such a chart is read at a stride (relief_raster.cpp).
  ReliefEnvelopes envelopes;
  // A smooth chart's grid: intervals along the object's longer side (layGridUnder; 8 at least).
  int grid_intervals = kSmoothChartIntervals;
  tex::SampleOptions sampling;
  // The tile (metres per uv) the map's normals were made for (MeshContactOptions::normals_made_for_m).
  Eigen::Vector2d normals_made_for_m = Eigen::Vector2d::Zero();
};

// Attaches `relief` (which must outlive the shape) to a btBvhTriangleMeshShape built from its mesh.
void attachMeshRelief(btCollisionShape& mesh_shape, const MeshRelief& relief);
// The relief attached to a mesh shape; nullptr for any other shape.
const MeshRelief* meshReliefOf(const btCollisionShape& shape);

// A pole of the uv (a lathe's axis, a UV sphere's pole): one position whose copies hold the
// texture coordinates of a row (u all round, v alike), so the uv is not continuous across the
// edges of the fan of triangles round it (each such edge's end there has another u on either
// side). kPoleFan: a triangle of that fan; kPoleRing: one sharing a corner's position with it.
inline constexpr std::uint8_t kPoleFan = 2, kPoleRing = 1;
std::vector<std::uint8_t> poleFans(const ContactMesh& mesh);

struct MeshChart {
  tex::TexturedSurface surface;  // its plane frame is the chart, placed in the mesh's frame
  GroundBend bend;               // the smooth surface's height above the chart (chart frame)
  std::uint32_t triangle = 0;    // the foot's triangle
  double side = 1.0;             // -1: the chart faces against the mesh's winding (a smooth chart only)
  bool smooth = false;           // nothing laid on it (smoothChartMap): its samples laid by layGridUnder
  double least_cell_m = 0.0;     // by a pole: the relief's coarser texel, a textured object's grid cells may be that long
};

// The chart under the point c (mesh frame) of an object reaching `reach_m` from it, starting the
// walk at `triangle` (updated to the foot's; kNoNeighbour: from the nearest triangle, found by
// looking at every one). False where c lies behind the winding of a relief mesh. A smooth chart's
// plane is laid by layGridUnder afterwards.
//
// By a pole of the uv a relief's chart is smooth (nothing laid on it): the texture has no one
// layout there. A chart laid at the foot took the u and the tangent of the fan's triangle under
// it, which differ from one triangle to the next (by up to 1/128 of the way round the bowl of bricks),
// so the texture laid under an object turned and slid as its foot crossed the fan's edges, and a
// bump-mapped ball at the bowl's centre never came to rest. `by_pole` (the object's, kept between
// steps) holds which: set where the foot is on the fan, cleared where it is beyond the fan's ring
// of neighbours, kept on that ring, so that an object resting by the fan's edge stays on one.
bool chartUnder(const MeshRelief& relief, const Eigen::Vector3d& c, double reach_m, std::uint32_t& triangle,
                bool& by_pole, MeshChart& out);

// The triangle chartUnder's walk starts from for an object centred at c (mesh frame) whose bounds
// widened by its contact threshold are `reach`: `foot`, the foot's triangle kept from the step
// before, while its point nearest c lies within `reach` and c lies in front of it (where the mesh
// has a relief); else the nearest triangle within `reach` (mesh::nearestTriangle's answer there),
// asked of the mesh's Bullet BVH `triangles`; mesh::kNoNeighbour where none is (nothing to meet).
// A foot kept while the object was beyond the mesh's bounds, then back on the far side of a closed
// mesh, lies behind it: against that face's plane the object read as behind the winding, no chart
// was found and the foot was never moved again; two bump-mapped balls passed through each other.
// (A rod tipping over a box's edge, its centre gone below the top face, now meets the side face
// under it, where it fell free of the box before.)
std::uint32_t footToWalkFrom(const MeshRelief& relief, const btConcaveShape& triangles, const Eigen::Vector3d& c,
                             const Eigen::AlignedBox3d& reach, std::uint32_t foot);

// The chart of a surface across a crease from the one under the object (chart_boundary.hpp): at the
// point of `triangle` nearest c, on the side `side` of the winding (the chart under the object's),
// without walking (a walk would cross the crease back). False where c does not lie in front of it
// on that side: an object behind a face's plane cannot touch its front (the grooved block resting
// short of a slab's edge, met by the side face's chart from behind, would read its whole width as
// depth).
bool chartOnFace(const MeshRelief& relief, const Eigen::Vector3d& c, double reach_m, std::uint32_t triangle,
                 double side, MeshChart& out);

// A smooth chart on a flat plane (a plain plane's, plain_plane.hpp): the plane's frame (normal +z)
// placed at `plane_from_chart`, no bend; its samples laid by layGridUnder afterwards.
MeshChart flatSmoothChart(const Eigen::Isometry3d& plane_from_chart);

// Whether the chart is a smooth one (its map is smoothChartMap()).
bool isSmoothChart(const tex::TexturedSurface& surface);

// Turns a smooth chart about its normal so that x runs along `axis` (mesh frame) projected on it.
void alignChart(MeshChart& chart, const Eigen::Vector3d& axis);

// Lays a smooth chart's samples over `footprint` (the object's underside in the chart's plane
// frame): a grid of `intervals` along its longer side and as many of about the same spacing
// along the other (two at least), its first and last rows and columns on the footprint's edges
// (a hair inside, so the object is there); more where a cell would be longer than `max_cell_m`
// (a textured box's own texel), up to kMaxGridIntervals; never fewer than kMinGridIntervals (at 4
// a capsule in a pipe, two rows across it and cells 13 mm along, gained its swing 8.7 times over).
inline constexpr int kMinGridIntervals = 8, kMaxGridIntervals = 512;
void layGridUnder(MeshChart& chart, const Eigen::AlignedBox2d& footprint, int intervals,
                  double max_cell_m = std::numeric_limits<double>::infinity());

// The triangle under a point on the smooth surface near the foot's triangle (for the contact's
// place, as Bullet reports a triangle for its own points).
std::uint32_t triangleUnder(const MeshRelief& relief, const Eigen::Vector3d& p, std::uint32_t from);

}  // namespace thx::phys
