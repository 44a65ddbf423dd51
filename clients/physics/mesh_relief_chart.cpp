#include "clients/physics/mesh_relief_chart.hpp"

#include <BulletCollision/BroadphaseCollision/btBroadphaseProxy.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <unordered_map>
#include <unordered_set>

#include "clients/physics/chart_boundary.hpp"
#include "meshes/position_key.hpp"

namespace thx::phys {

namespace {

// Edges from one position whose uv breaks at that end alone (each counted from both sides) that
// make it a pole: 4 edges, a UV sphere of 4 segments' (every edge from a pole breaks so). Where
// an atlas's seams meet, fewer break at one end alone (tests/physics/test_pole_fans.cpp).
constexpr int kPoleEdges = 8;

constexpr int kMeshReliefTag = 0x7468584d;  // "thXM": the user index marking an attached MeshRelief

// The smooth chart's map: flat, nothing laid on the surface (a relief map, so that the raster
// reads heights; every depth 0).
const tex::TextureMap& smoothChartMap() {
  static const tex::TextureMap flat(2, 2, tex::Representation::Relief, 1e-3);
  return flat;
}

// The bend's least-squares fit h = (xx x^2 + 2 xy x y + yy y^2) / 2 to the smooth surface's
// heights at eight points a distance `radius` round the foot (their feet on Phong's surface),
// in the chart's axes (x, y, its normal n; `side` -1: n against the winding). A point whose foot
// lies across a crease from the chart (chart_boundary.hpp) is not the chart's surface and is left
// out: by a slab's edge the ring's points past it walked onto the side face, and the bend bowed
// the top's chart down so that a block resting there by the edge was thrown back. Flat where too
// few points are left to fit.
GroundBend fitBend(const ContactMesh& cm, const Eigen::Vector3d& foot, const Eigen::Matrix3d& axes,
                   std::uint32_t triangle, double radius, double side) {
  Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
  Eigen::Vector3d atb = Eigen::Vector3d::Zero();
  int used = 0;
  for (int k = 0; k < 8; ++k) {
    const double a = k * std::numbers::pi / 4;
    const Eigen::Vector3d p = foot + radius * (std::cos(a) * axes.col(0) + std::sin(a) * axes.col(1));
    std::uint32_t t = triangle;
    Eigen::Vector3d b(1.0 / 3, 1.0 / 3, 1.0 / 3);
    smoothFoot(cm, p, 1.0, t, b);
    if (acrossCrease(cm, t, side * axes.col(2))) continue;
    const Eigen::Vector3d d = mesh::frameAt(*cm.mesh, t, b, mesh::FrameMode::InterpolatedPhong).point - foot;
    const double x = d.dot(axes.col(0)), y = d.dot(axes.col(1)), h = d.dot(axes.col(2));
    const Eigen::Vector3d row(0.5 * x * x, x * y, 0.5 * y * y);
    ata += row * row.transpose();
    atb += row * h;
    ++used;
  }
  GroundBend bend;
  if (used < 4) {
    bend.known = false;
    return bend;
  }
  const Eigen::Vector3d q = ata.ldlt().solve(atb);
  if (q.allFinite()) bend.xx = q[0], bend.xy = q[1], bend.yy = q[2];
  return bend;
}

}  // namespace

std::vector<std::uint8_t> poleFans(const ContactMesh& contact_mesh) {
  const mesh::TexturedMesh& m = *contact_mesh.mesh;
  // The same place in the texture: uv differing by whole tiles (a wrapped seam) or not at all.
  auto sameTexel = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector2d d = a - b;
    return (d - d.array().round().matrix()).cwiseAbs().maxCoeff() < 1e-9;
  };
  // The uv of `triangle`'s corner at position p (nullptr where none is there).
  auto uvAt = [&](std::uint32_t triangle, const Eigen::Vector3d& p) -> const Eigen::Vector2d* {
    for (std::uint32_t v : m.triangles[triangle])
      if (m.positions[v] == p) return &m.uvs[v];
    return nullptr;
  };
  // Each edge where one end's uv continues across and the other's does not, counted at the end
  // that does not (once from each side). Round a pole every edge from it is one; an atlas's
  // corner (a cube-sphere's, a box's) has a few at most, its seams breaking both ends or one by
  // chance.
  std::unordered_map<mesh::PositionBits, int, mesh::PositionHash> broken;
  for (std::uint32_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t across = contact_mesh.neighbours[t][std::size_t(k)];
      if (across == mesh::kNoNeighbour) continue;
      const std::uint32_t a = m.triangles[t][std::size_t((k + 1) % 3)], b = m.triangles[t][std::size_t((k + 2) % 3)];
      const Eigen::Vector2d *ua = uvAt(across, m.positions[a]), *ub = uvAt(across, m.positions[b]);
      if (!ua || !ub) continue;
      const bool same_a = sameTexel(m.uvs[a], *ua), same_b = sameTexel(m.uvs[b], *ub);
      if (same_a != same_b) ++broken[mesh::bitsOf(m.positions[same_a ? b : a])];
    }
  std::unordered_set<mesh::PositionBits, mesh::PositionHash> poles;
  for (const auto& [at, edges] : broken)
    if (edges >= kPoleEdges) poles.insert(at);
  std::vector<std::uint8_t> pole(m.triangles.size(), 0);
  if (poles.empty()) return pole;
  std::unordered_set<mesh::PositionBits, mesh::PositionHash> fan_corners;
  for (std::uint32_t t = 0; t < m.triangles.size(); ++t)
    for (std::uint32_t v : m.triangles[t])
      if (poles.count(mesh::bitsOf(m.positions[v]))) {
        pole[t] = kPoleFan;
        for (std::uint32_t w : m.triangles[t]) fan_corners.insert(mesh::bitsOf(m.positions[w]));
        break;
      }
  // The fan's ring: triangles sharing a corner's position with a fan triangle.
  for (std::uint32_t t = 0; t < m.triangles.size(); ++t)
    if (pole[t] == 0)
      for (std::uint32_t v : m.triangles[t])
        if (fan_corners.count(mesh::bitsOf(m.positions[v]))) pole[t] = kPoleRing;
  return pole;
}

MeshRelief::MeshRelief(const mesh::TexturedMesh& m) : mesh(m), pole(poleFans(mesh)) {}

void attachMeshRelief(btCollisionShape& mesh_shape, const MeshRelief& relief) {
  mesh_shape.setUserPointer(const_cast<MeshRelief*>(&relief));
  mesh_shape.setUserIndex(kMeshReliefTag);
}

const MeshRelief* meshReliefOf(const btCollisionShape& shape) {
  if (shape.getShapeType() != TRIANGLE_MESH_SHAPE_PROXYTYPE || shape.getUserIndex() != kMeshReliefTag) return nullptr;
  return static_cast<const MeshRelief*>(shape.getUserPointer());
}

namespace {

// The chart at the foot f (on `triangle`, barycentric b) of an object reaching `reach_m`, on the
// side `side` of the winding (a relief's chart is on the winding's side only); smooth where the
// caller has set out.smooth.
void layChartAt(const MeshRelief& relief, std::uint32_t triangle, const Eigen::Vector3d& b, const mesh::SurfaceFrame& f,
                double side, double reach_m, MeshChart& out) {
  out.triangle = triangle;
  out.side = side;
  out.least_cell_m = 0.0;
  if (out.smooth) {
    // Nothing laid on it: the frame is the smooth normal on the object's side and any tangent
    // (alignChart turns it, layGridUnder places its samples).
    const Eigen::Vector3d n = side * f.normal;
    Eigen::Vector3d x = f.tangent - f.tangent.dot(n) * n;
    if (!(x.norm() > 1e-9)) x = n.unitOrthogonal();
    Eigen::Matrix3d axes;
    axes.col(0) = x.normalized(), axes.col(2) = n, axes.col(1) = n.cross(axes.col(0));
    tex::PlaneMapping mapping;
    mapping.plane_to_world.linear() = axes;
    mapping.plane_to_world.translation() = f.point;
    out.surface = tex::TexturedSurface(smoothChartMap(), mapping, tex::SampleOptions{}, true);
    out.bend = fitBend(relief.mesh, f.point, axes, triangle, reach_m, side);
    out.bend.centre = Eigen::Vector2d::Zero();
    // By a pole, a textured object's grid cells as long as the relief's coarser texel there (not
    // its own texel's), as the relief's chart would read it: at a bump-mapped ball's own texels
    // (61 um) a step cost five times as much.
    if (relief.map) {
      const Eigen::Vector2d scale = metresPerUvAt(relief.mesh, triangle, b);
      out.least_cell_m = std::max(scale.x() / relief.map->width(), scale.y() / relief.map->height());
    }
    return;
  }
  // The chart as the pen's (hapticd's chartAt): x along the tangent, y along the bitangent, uv
  // taken within its tile so the chart's origin stays near; but the texture at the scale its
  // vertices' faces lay it at, interpolated to the foot (metresPerUvAt, as the lifted ball reads
  // it), not at the foot's face's own (mesh::metresPerUv, the pen's), so that it does not jump at
  // an edge. Near a lathe's pole the face's own scale halves across every other edge (a face's u
  // edge on the ring of the pole's fan, or on the ring beyond: 2.52 and 1.26 mm per uv on the
  // bowl of bricks), and the texture laid under an object there jumped each time its foot
  // crossed one: a bump-mapped ball resting 2.4 mm from the pole was thrown up by 7 um each time.
  const Eigen::Vector2d scale = metresPerUvAt(relief.mesh, triangle, b);
  const Eigen::Vector2d uv = f.uv - f.uv.array().floor().matrix();
  tex::PlaneMapping mapping;
  mapping.size_m = scale;
  Eigen::Matrix3d axes;
  axes.col(0) = f.tangent, axes.col(1) = f.bitangent, axes.col(2) = f.normal;
  mapping.plane_to_world.linear() = axes;
  const Eigen::Vector2d foot((uv.x() - 0.5) * scale.x(), (uv.y() - 0.5) * scale.y());
  mapping.plane_to_world.translation() = f.point - f.tangent * foot.x() - f.bitangent * foot.y();
  // Where the uv squeezes the texture along one axis, its envelope merged along that axis
  // (relief_envelope.hpp): the same tile, its texels about square on the chart.
  const tex::TextureMap& map = envelopeFor(relief.envelopes, *relief.map, scale.x() / relief.map->width(),
                                           scale.y() / relief.map->height());
  out.surface = tex::TexturedSurface(map, mapping, relief.sampling, true);
  out.surface.setNormalsMadeFor(relief.normals_made_for_m);
  out.bend = fitBend(relief.mesh, f.point, axes, triangle, reach_m, side);
  out.bend.centre = foot;
}

}  // namespace

bool chartUnder(const MeshRelief& relief, const Eigen::Vector3d& c, double reach_m, std::uint32_t& triangle,
                bool& by_pole, MeshChart& out) {
  const mesh::TexturedMesh& m = *relief.mesh.mesh;
  if (triangle >= m.triangles.size()) triangle = mesh::nearestTriangle(m, c);
  Eigen::Vector3d b = mesh::closestBarycentric(m, triangle, c);
  // The winding's side first, then the foot along the smooth normal on that side.
  const mesh::SurfaceFrame near = mesh::frameAt(m, triangle, b, mesh::FrameMode::Interpolated);
  const double side = (c - near.point).dot(near.normal) < 0.0 ? -1.0 : 1.0;
  if (side < 0.0 && relief.map) return false;
  smoothFoot(relief.mesh, c, side, triangle, b);
  const mesh::SurfaceFrame f = mesh::frameAt(m, triangle, b, mesh::FrameMode::InterpolatedPhong);
  if (side * (c - f.point).dot(f.normal) < 0.0) return false;
  if (relief.pole[triangle] == kPoleFan) by_pole = true;
  else if (relief.pole[triangle] == 0) by_pole = false;
  out.smooth = !relief.map || by_pole;
  layChartAt(relief, triangle, b, f, side, reach_m, out);
  return true;
}

namespace {

// The nearest to c of the triangles Bullet's BVH hands over (their boxes meet the query's).
struct NearestTriangle : btTriangleCallback {
  NearestTriangle(const mesh::TexturedMesh& m, const Eigen::Vector3d& centre) : mesh(m), c(centre) {}
  void processTriangle(btVector3*, int, int index) override {
    const auto t = std::uint32_t(index);
    if (t >= mesh.triangles.size()) return;
    // As mesh::nearestTriangle reads it, the first of equals in the mesh's order: its answer
    // wherever the nearest lies within reach, whatever order the BVH hands them in.
    const double d = (mesh::pointAt(mesh, t, mesh::closestBarycentric(mesh, t, c)) - c).squaredNorm();
    if (d < best_d || (d == best_d && t < best)) best_d = d, best = t;
  }
  const mesh::TexturedMesh& mesh;
  Eigen::Vector3d c;
  double best_d = std::numeric_limits<double>::infinity();
  std::uint32_t best = mesh::kNoNeighbour;
};

}  // namespace

std::uint32_t footToWalkFrom(const MeshRelief& relief, const btConcaveShape& triangles, const Eigen::Vector3d& c,
                             const Eigen::AlignedBox3d& reach, std::uint32_t foot) {
  const mesh::TexturedMesh& m = *relief.mesh.mesh;
  if (foot < m.triangles.size()) {
    const mesh::SurfaceFrame near = mesh::frameAt(m, foot, mesh::closestBarycentric(m, foot, c), mesh::FrameMode::Interpolated);
    const bool in_front = !relief.map || (c - near.point).dot(near.normal) >= 0.0;
    if (in_front && reach.exteriorDistance(near.point) == 0.0) return foot;
  }
  NearestTriangle nearest(m, c);
  triangles.processAllTriangles(&nearest, btVector3(btScalar(reach.min().x()), btScalar(reach.min().y()), btScalar(reach.min().z())),
                                btVector3(btScalar(reach.max().x()), btScalar(reach.max().y()), btScalar(reach.max().z())));
  return nearest.best;
}

bool chartOnFace(const MeshRelief& relief, const Eigen::Vector3d& c, double reach_m, std::uint32_t triangle,
                 double side, MeshChart& out) {
  const mesh::TexturedMesh& m = *relief.mesh.mesh;
  if (triangle >= m.triangles.size() || (relief.map && side < 0.0)) return false;
  const Eigen::Vector3d b = mesh::closestBarycentric(m, triangle, c);
  const mesh::SurfaceFrame f = mesh::frameAt(m, triangle, b, mesh::FrameMode::InterpolatedPhong);
  if (side * (c - f.point).dot(f.normal) <= 0.0) return false;
  out.smooth = !relief.map || relief.pole[triangle] == kPoleFan;
  layChartAt(relief, triangle, b, f, side, reach_m, out);
  return true;
}

MeshChart flatSmoothChart(const Eigen::Isometry3d& plane_from_chart) {
  MeshChart out;
  tex::PlaneMapping mapping;
  mapping.plane_to_world = plane_from_chart;
  out.surface = tex::TexturedSurface(smoothChartMap(), mapping, tex::SampleOptions{}, true);
  out.smooth = true;
  return out;
}

bool isSmoothChart(const tex::TexturedSurface& surface) { return &surface.map() == &smoothChartMap(); }

void alignChart(MeshChart& chart, const Eigen::Vector3d& axis) {
  const Eigen::Isometry3d& mesh_from_chart = chart.surface.mapping().plane_to_world;
  const Eigen::Vector3d n = mesh_from_chart.linear().col(2);
  const Eigen::Vector3d x = axis - axis.dot(n) * n;
  if (!(x.norm() > 1e-6 * axis.norm())) return;  // the axis along the normal: any turn will do
  // The bend is a quadratic form in the chart's axes: turned with them, about the chart's origin.
  const Eigen::Vector2d along(x.dot(mesh_from_chart.linear().col(0)), x.dot(mesh_from_chart.linear().col(1)));
  const double angle = std::atan2(along.y(), along.x());
  const Eigen::Matrix2d turn = Eigen::Rotation2Dd(angle).toRotationMatrix();
  Eigen::Matrix2d form;
  form << chart.bend.xx, chart.bend.xy, chart.bend.xy, chart.bend.yy;
  form = turn.transpose() * form * turn;
  chart.bend.xx = form(0, 0), chart.bend.xy = form(0, 1), chart.bend.yy = form(1, 1);
  chart.bend.centre = turn.transpose() * chart.bend.centre;
  tex::PlaneMapping mapping = chart.surface.mapping();
  mapping.plane_to_world.linear() = mesh_from_chart.linear() * Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  chart.surface = tex::TexturedSurface(chart.surface.map(), mapping, chart.surface.sampling(), true);
}

void layGridUnder(MeshChart& chart, const Eigen::AlignedBox2d& footprint, int intervals, double max_cell_m) {
  const Eigen::Vector2d extent = footprint.sizes();
  const double longer = std::max(extent.maxCoeff(), 1e-9);
  // Enough for a cell no longer than max_cell_m (none for an infinite one).
  const double fine = std::min(std::ceil(longer / max_cell_m), double(kMaxGridIntervals));
  const int n = std::clamp(std::max(intervals, int(fine)), kMinGridIntervals, kMaxGridIntervals);
  // About square cells (the raster reads a chart whose cells differ more than twice at the
  // coarser spacing), each side an exact number of them, at least two, so that a level rod has a
  // row of samples under its axis.
  const Eigen::Vector2d count(std::max(2.0, std::round(n * extent.x() / longer)), std::max(2.0, std::round(n * extent.y() / longer)));
  // Samples a hair inside the edges: on them the object's underside may read as absent.
  const Eigen::Vector2d inset = 1e-7 * extent;
  const Eigen::Vector2d step = (extent - 2.0 * inset).cwiseMax(Eigen::Vector2d::Constant(1e-9)).cwiseQuotient(count);
  tex::PlaneMapping mapping = chart.surface.mapping();
  const tex::TextureMap& map = chart.surface.map();
  mapping.size_m = Eigen::Vector2d(step.x() * map.width(), step.y() * map.height());
  // The centre of texel (0, 0) (top left: +j is -y) on the footprint's corner at (min x, max y).
  const tex::TexturedSurface unplaced(map, mapping, chart.surface.sampling(), true);
  const Eigen::Vector2d first = unplaced.texelCentre(0, 0).head<2>();
  const Eigen::Vector2d corner(footprint.min().x() + inset.x(), footprint.max().y() - inset.y());
  const Eigen::Vector2d shift = corner - first;  // the plane's origin moves here; every plane point by -shift
  mapping.plane_to_world.translation() += mapping.plane_to_world.linear().leftCols<2>() * shift;
  chart.surface = tex::TexturedSurface(map, mapping, chart.surface.sampling(), true);
  chart.bend.centre -= shift;
}

std::uint32_t triangleUnder(const MeshRelief& relief, const Eigen::Vector3d& p, std::uint32_t from) {
  Eigen::Vector3d b(1.0 / 3, 1.0 / 3, 1.0 / 3);
  smoothFoot(relief.mesh, p, 1.0, from, b);
  return from;
}

}  // namespace thx::phys
