#include "clients/physics/chart_boundary.hpp"

#include <BulletCollision/CollisionShapes/btTriangleCallback.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "clients/physics/bullet_convert.hpp"
#include "clients/physics/mesh_contact.hpp"

namespace thx::phys {

namespace {

// Two planes closer than this in direction (unit normals' difference) and offset (metres) are one.
constexpr double kSameDirection = 1e-6, kSameOffset = 1e-7;
// A neighbour this much nearer the object's centre (metres) is nearer (a smooth sphere mesh of a
// millimetre's faces differ by micrometres there).
constexpr double kNearer = 1e-9;
// A face across a crease from the chart has a normal whose cosine to the chart's is below this.
const double kCreaseCosine = std::cos(kCreaseFromChartDeg * std::numbers::pi / 180.0);

struct CollectEdges : btTriangleCallback {
  const ContactMesh& contact_mesh;
  const mesh::TexturedMesh& mesh;
  const Eigen::Isometry3d& mesh_from_chart;
  Eigen::Vector2d inside;
  Eigen::Vector3d centre;
  Eigen::Vector3d chart_normal;  // mesh frame, on the winding's side
  double side;
  double reach_radius;
  ChartBoundary& out;
  // Every surface found, before the nearest kMaxSurfaces are kept.
  std::array<BeyondSurface, 2 * ChartBoundary::kMaxSurfaces> found{};
  std::size_t found_count = 0;
  CollectEdges(const ContactMesh& m, const Eigen::Isometry3d& c, const Eigen::Vector2d& f,
               const Eigen::Vector3d& o_centre, double s, double r, ChartBoundary& o)
      : contact_mesh(m), mesh(*m.mesh), mesh_from_chart(c), inside(f), centre(o_centre),
        chart_normal(s * c.linear().col(2)), side(s), reach_radius(r), out(o) {}

  // How far the triangle's closest point lies from the object's centre.
  double distanceOf(std::uint32_t index) const {
    const mesh::Triangle& t = mesh.triangles[index];
    const Eigen::Vector3d b = mesh::closestBarycentric(mesh, index, centre);
    return (b[0] * mesh.positions[t[0]] + b[1] * mesh.positions[t[1]] + b[2] * mesh.positions[t[2]] - centre).norm();
  }

  // The triangle joins the first surface it is not across a crease from, or starts one.
  void gather(std::uint32_t index, const Eigen::Vector3d& n, double distance) {
    for (std::size_t k = 0; k < found_count; ++k) {
      BeyondSurface& s = found[k];
      if (acrossCrease(contact_mesh, index, s.normal)) continue;
      if (distance < s.distance_m) s.nearest_triangle = index, s.distance_m = distance;
      return;
    }
    if (found_count < found.size()) {
      found[found_count++] = {n, index, distance};
      return;
    }
    // Full: the new surface takes the place of the farthest, if it is nearer.
    BeyondSurface* farthest = std::max_element(found.begin(), found.end(), [](const BeyondSurface& p, const BeyondSurface& q) {
      return p.distance_m < q.distance_m;
    });
    if (distance < farthest->distance_m) *farthest = {n, index, distance};
  }

  // Whether the mesh is smooth across the edge of `index` opposite its corner k: the triangle
  // across it has the same normals at the edge's ends (a hard edge splits them; a texture seam
  // does not).
  bool smoothAcross(std::uint32_t index, int k, std::uint32_t other) const {
    const mesh::Triangle& t = mesh.triangles[index];
    const mesh::Triangle& o = mesh.triangles[other];
    for (int end = 1; end <= 2; ++end) {
      const std::uint32_t v = t[std::size_t((k + end) % 3)];
      bool same = false;
      for (std::uint32_t w : o)
        if (mesh.positions[w] == mesh.positions[v]) same = (mesh.normals[w] - mesh.normals[v]).norm() < kSameDirection;
      if (!same) return false;
    }
    return true;
  }

  // Whether the surface of `index`, `distance` from the object's centre at its nearest point, runs
  // on smoothly to a triangle nearer still: across edges the mesh is smooth across, from the
  // triangle to one as near (round the fan of a corner where the nearest point is that corner) and
  // on to one nearer. Then the object's nearest point on that smooth surface is not here, and the
  // surface is the chart's own, turned past the crease angle: a sphere mesh curved more tightly
  // than the object on it (a 1 cm ball on a 1 mm sphere) has no crease, yet its faces 60 degrees
  // round from the foot lie within the ball's reach, and their charts, tangent planes run on far
  // past the sphere, read the ball 0.4-2.6 mm deep and threw it off at 0.5-0.8 m/s. Across a hard
  // edge (a slab's top against its side) the nearest points of both faces meet on the edge, and
  // neither is nearer.
  bool runsOnNearer(std::uint32_t index, double distance) const {
    std::uint32_t current = index, previous = mesh::kNoNeighbour;
    for (int hop = 0; hop < contact_mesh.max_hops; ++hop) {
      const Eigen::Vector3d b = mesh::closestBarycentric(mesh, current, centre);
      std::uint32_t level = mesh::kNoNeighbour;
      for (int k = 0; k < 3; ++k) {
        if (b[k] > 0.0) continue;  // the nearest point is not on the edge opposite corner k
        const std::uint32_t other = contact_mesh.neighbours[current][std::size_t(k)];
        if (other == mesh::kNoNeighbour || other == previous || !smoothAcross(current, k, other)) continue;
        const double d = distanceOf(other);
        if (d < distance - kNearer) return true;
        if (d <= distance + kNearer) level = other;
      }
      if (level == mesh::kNoNeighbour) return false;
      previous = current, current = level;
    }
    return false;
  }

  void keepNearest() {
    const auto runs_on = std::remove_if(found.begin(), found.begin() + std::ptrdiff_t(found_count),
                                        [&](const BeyondSurface& s) { return runsOnNearer(s.nearest_triangle, s.distance_m); });
    found_count = std::size_t(runs_on - found.begin());
    std::sort(found.begin(), found.begin() + std::ptrdiff_t(found_count),
              [](const BeyondSurface& a, const BeyondSurface& b) { return a.distance_m < b.distance_m; });
    out.surface_count = std::min(found_count, ChartBoundary::kMaxSurfaces);
    std::copy_n(found.begin(), out.surface_count, out.surfaces.begin());
  }

  void processTriangle(btVector3* triangle, int, int index) override {
    if (index < 0 || std::size_t(index) >= mesh.triangles.size()) return;
    if (!acrossCrease(contact_mesh, std::uint32_t(index), chart_normal)) return;
    // A face the object cannot reach neither holds it nor cuts its chart: the reach box's corners
    // hold faces of a tight curve far round from the foot (see chartBoundary).
    const double distance = distanceOf(std::uint32_t(index));
    if (distance > reach_radius) return;
    const Eigen::Vector3d& n = contact_mesh.face_normals[std::size_t(index)];
    gather(std::uint32_t(index), n, distance);
    // Full: no further edge is kept (a sphere mesh smaller than the object has every face within
    // its reach, and each face its own plane).
    if (out.count == ChartBoundary::kMaxEdges) return;
    const Eigen::Vector3d p0 = toEigen(triangle[0]);
    // The face's plane n . x = d met by the chart's plane z = 0: x = R p + t gives the line
    // (R^T n)_xy . p = d - n . t.
    const Eigen::Vector3d along = mesh_from_chart.linear().transpose() * n;
    const Eigen::Vector2d line = along.head<2>();
    const double length = line.norm();
    if (length < 1e-9) return;  // parallel to the chart (a plate's underside): no line to cut along
    const double plane_offset = n.dot(p0) - n.dot(mesh_from_chart.translation());  // d - n . t
    ChartEdge edge;
    edge.normal = line / length;
    edge.offset = plane_offset / length;
    // Oriented so that the chart's own face is held.
    if (edge.normal.dot(inside) > edge.offset) edge.normal = -edge.normal, edge.offset = -edge.offset;
    // The face's plane in the chart's frame, its normal out of the solid on the chart's side of the
    // winding; convex where the chart's own face lies behind it.
    edge.across_normal = side * along;
    edge.across_offset = side * plane_offset;
    edge.convex = edge.across_normal.head<2>().dot(inside) < edge.across_offset;
    for (std::size_t k = 0; k < out.count; ++k)
      if ((out.edges[k].normal - edge.normal).norm() < kSameDirection && std::fabs(out.edges[k].offset - edge.offset) < kSameOffset)
        return;
    if (out.count < ChartBoundary::kMaxEdges) out.edges[out.count++] = edge;
  }
};

}  // namespace

bool ChartBoundary::past(const Eigen::Vector3d& p) const {
  for (std::size_t k = 0; k < count; ++k)
    if (edges[k].normal.dot(p.head<2>()) > edges[k].offset) return true;
  return false;
}

bool ChartBoundary::nearerAcross(const Eigen::Vector3d& q, double gap) const {
  for (std::size_t k = 0; k < count; ++k)
    if (edges[k].convex && edges[k].across_normal.dot(q) - edges[k].across_offset > gap) return true;
  return false;
}

bool acrossCrease(const ContactMesh& mesh, std::uint32_t triangle, const Eigen::Vector3d& chart_normal) {
  return mesh.face_normals[triangle].dot(chart_normal) < kCreaseCosine;
}

ChartBoundary chartBoundary(const btConcaveShape& mesh_shape, const ContactMesh& mesh,
                            const Eigen::Isometry3d& mesh_from_chart, const Eigen::Vector2d& inside,
                            const Eigen::AlignedBox3d& reach, const Eigen::Vector3d& centre, double reach_radius,
                            double side) {
  ChartBoundary boundary;
  CollectEdges collect(mesh, mesh_from_chart, inside, centre, side, reach_radius, boundary);
  mesh_shape.processAllTriangles(&collect, toBt(reach.min()), toBt(reach.max()));
  collect.keepNearest();
  return boundary;
}

bool offChart(const ChartBoundary* boundary, const ReliefCandidate& c) {
  return boundary && boundary->count > 0 &&
         (boundary->past(c.p_surface) || boundary->nearerAcross(c.p_surface + c.depth * Eigen::Vector3d::UnitZ(), c.depth));
}

void dropPastBoundary(const ChartBoundary* boundary, std::vector<ReliefCandidate>& candidates) {
  if (!boundary || boundary->count == 0) return;
  std::erase_if(candidates, [&](const ReliefCandidate& c) { return offChart(boundary, c); });
}

}  // namespace thx::phys
