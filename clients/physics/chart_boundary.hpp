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
// side of that line that holds the middle of its foot's triangle. The object meets such a face as
// Bullet's triangles (flat, untextured; relief_collision.cpp), which lie at the relief's top: an
// object down in its grooves reads their depth as penetration there (docs/physics.md, Known gaps).
#include <BulletCollision/CollisionShapes/btConcaveShape.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <cstdint>

#include "meshes/textured_mesh.hpp"

namespace thx::phys {

inline constexpr double kCreaseFromChartDeg = 60.0;

// A line of the chart's plane (chart frame, metres): the chart holds the points with
// normal . p < offset.
struct ChartEdge {
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();
  double offset = 0.0;
};

struct ChartBoundary {
  static constexpr std::size_t kMaxEdges = 8;  // distinct planes across creases within an object's reach
  std::array<ChartEdge, kMaxEdges> edges{};
  std::size_t count = 0;
  bool beyond_faces = false;  // some face across a crease lies within reach (even parallel to the chart)

  // Whether the chart point p (chart frame; its z ignored) lies past an edge, or within `margin`
  // of one (metres).
  bool past(const Eigen::Vector3d& p, double margin = 0.0) const;
};

// Whether the mesh's `triangle` lies across a crease from a chart whose normal is `chart_normal`
// (mesh frame).
bool acrossCrease(const mesh::TexturedMesh& mesh, std::uint32_t triangle, const Eigen::Vector3d& chart_normal);

// The edges of the chart `mesh_from_chart` cut by the faces across a crease among the triangles of
// `mesh` (the one `mesh_shape` was built from) that overlap `reach` (mesh frame). `inside` (chart frame) is a point of the chart's own
// face, the middle of the foot's triangle: the side of each edge that holds it is the chart's (the
// foot itself may lie on the crease, where an object's centre has passed beyond a box's edge).
// `side` -1: the chart faces against the mesh's winding (a smooth chart behind it: its faces are
// compared with the chart's normal turned back to the winding's side).
ChartBoundary chartBoundary(const btConcaveShape& mesh_shape, const mesh::TexturedMesh& mesh,
                            const Eigen::Isometry3d& mesh_from_chart, const Eigen::Vector2d& inside,
                            const Eigen::AlignedBox3d& reach, double side = 1.0);

}  // namespace thx::phys
