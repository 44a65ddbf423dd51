#pragma once
// Where a relief mesh's chart stops (mesh_relief_chart.hpp): one chart holds the smooth surface
// under an object's centre, and its plane runs on past a crease of the mesh (a box's edge, a
// bowl's rim, a tray's inside corner) where the mesh turns away. There the chart's relief is not
// the mesh: an object hanging over a slab's edge with its centre over the side face met the side's
// plane, run on up above the top, 7 mm deep, and was thrown off at 1.4 m/s.
//
// A face across a crease from the chart is one whose normal lies more than kCreaseFromChartDeg
// from the chart's (the default angle at which the mesh's own frames keep an edge hard,
// meshes/textured_mesh.hpp); it cuts the chart's plane along a line, and the chart holds only the
// side of that line that holds the middle of its foot's triangle. The faces across creases are
// gathered into surfaces (faces not across a crease from each other), each with its triangle
// nearest the object: the object meets each such surface on a chart of its own, cut the same way
// (relief_collision.cpp), so that the texture is read beyond the crease too. A surface whose
// nearest point runs on across edges the mesh is smooth across to faces nearer the object is no
// surface of its own but the chart's, curved past the crease angle (a sphere mesh smaller than
// the object on it); its faces still cut the chart.
#include <BulletCollision/CollisionShapes/btConcaveShape.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "clients/physics/contact_selection.hpp"
#include "clients/physics/mesh_contact.hpp"
#include "meshes/textured_mesh.hpp"

namespace thx::phys {

inline constexpr double kCreaseFromChartDeg = 60.0;

// A line of the chart's plane (chart frame, metres): the chart holds the points with
// normal . p < offset. It is where the plane of a face across a crease (across_normal . x =
// across_offset, chart frame, the normal out of the mesh's solid) meets the chart's; `convex`:
// the chart's own face lies behind that plane (a slab's top against its side), not in front of it
// (a room's floor against its wall).
struct ChartEdge {
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();
  double offset = 0.0;
  Eigen::Vector3d across_normal = Eigen::Vector3d::UnitX();
  double across_offset = 0.0;
  bool convex = true;
};

// A surface across a crease from the chart: faces within reach, none across a crease from the
// first one found (its face normal `normal`, mesh frame), and the one whose closest point lies
// nearest the object's centre.
struct BeyondSurface {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  std::uint32_t nearest_triangle = 0;
  double distance_m = 0.0;
};

struct ChartBoundary {
  static constexpr std::size_t kMaxEdges = 8;  // distinct planes across creases within an object's reach
  // Surfaces across creases kept (the nearest the object's centre first when there are more).
  static constexpr std::size_t kMaxSurfaces = 4;
  std::array<ChartEdge, kMaxEdges> edges{};
  std::size_t count = 0;
  std::array<BeyondSurface, kMaxSurfaces> surfaces{};
  std::size_t surface_count = 0;

  // Whether the chart point p (chart frame; its z ignored) lies past an edge.
  bool past(const Eigen::Vector3d& p) const;
  // Whether an object's point q (chart frame), `gap` from the chart's surface (negative: into it),
  // lies nearer a face across a convex crease than the chart: deeper behind the chart's surface
  // than behind that face's plane. Such a point is that face's to meet (on its own chart): a block
  // resting on a slab's top by its edge, sampled on the side face's chart, reads its whole width
  // as depth along the side's normal.
  bool nearerAcross(const Eigen::Vector3d& q, double gap) const;
};

// Whether the mesh's `triangle` lies across a crease from a chart whose normal is `chart_normal`
// (mesh frame).
bool acrossCrease(const ContactMesh& mesh, std::uint32_t triangle, const Eigen::Vector3d& chart_normal);

// The edges of the chart `mesh_from_chart` cut by the faces across a crease among the triangles of
// `mesh` (the one `mesh_shape` was built from) that overlap `reach` (mesh frame). `inside` (chart frame) is a point of the chart's own
// face, the middle of the foot's triangle: the side of each edge that holds it is the chart's (the
// foot itself may lie on the crease, where an object's centre has passed beyond a box's edge).
// `side` -1: the chart faces against the mesh's winding (a smooth chart behind it: its faces are
// compared with the chart's normal turned back to the winding's side). `centre` (mesh frame): the
// object's, to which each surface across a crease names its nearest triangle. A face farther
// from `centre` than `reach_radius` (the object's bounding radius and the breaking threshold) is
// not across a crease: it cannot hold the object. `reach` is a box, and on a mesh curved as tightly
// as the object its corners hold faces far round from the foot: on a smooth sphere mesh of a
// ball's own radius, faces 60 degrees round cut the chart and gave surfaces of their own, and the
// ball pressed on it along lines off the axes rested 173-640 um off its touch.
ChartBoundary chartBoundary(const btConcaveShape& mesh_shape, const ContactMesh& mesh,
                            const Eigen::Isometry3d& mesh_from_chart, const Eigen::Vector2d& inside,
                            const Eigen::AlignedBox3d& reach, const Eigen::Vector3d& centre, double reach_radius,
                            double side = 1.0);

// A chart's candidate past its boundary is not the mesh's. The basin walks find candidates by
// their texels' (i, j), so a gap in the raster is only a texel not there. Across a convex crease,
// a texel whose object point lies nearer the face across it than the chart goes too
// (ChartBoundary::nearerAcross): that face's chart meets it. A block resting on a slab's top by
// its edge, sunk a micrometre, read 7 mm into the side face's chart where its underside's edge was
// sampled, and was thrown back over the slab. (Dropping every texel within one texel of a crease
// instead dropped the ridge on a slab's edge, and a grooved block overhanging it tipped over the
// ridge before.) `boundary` null or without edges: nothing is off the chart.
bool offChart(const ChartBoundary* boundary, const ReliefCandidate& c);
void dropPastBoundary(const ChartBoundary* boundary, std::vector<ReliefCandidate>& candidates);

}  // namespace thx::phys
