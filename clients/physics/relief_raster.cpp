#include "clients/physics/relief_raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>

#include "clients/physics/chart_boundary.hpp"
#include "clients/physics/textured_box_rows.hpp"

namespace thx::phys {

namespace {

// A candidate's normal before withNormals reads it (hasNormal).
const Eigen::Vector3d kNoNormal = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());

// The part of the footprint that can touch the relief at all: the relief lies in
// [-maxDepth, 0], so only where the object reaches below z = threshold can a texel be a
// candidate. For a sphere that is a disc much smaller than the ball (at rest: radius
// sqrt(2 r (maxDepth + threshold))); other shapes keep their bounding box.
// A sphere's touching disc: the radius round its centre within which it reaches below `level`
// (its own radius where its centre is not above that level).
double touchingDiscRadius(const Underside& sphere, double level) {
  const double above = sphere.plane_from_object.translation().z() - level;  // centre's height above it
  return above > 0.0 ? std::sqrt(std::max(0.0, sphere.radius * sphere.radius - above * above)) : sphere.radius;
}

Eigen::AlignedBox2d touchingFootprint(const Underside& shape, const Eigen::AlignedBox3d& bounds, double threshold_m) {
  Eigen::AlignedBox2d box(bounds.min().head<2>(), bounds.max().head<2>());
  if (shape.kind == Underside::Kind::Sphere) {
    const Eigen::Vector3d c = shape.plane_from_object.translation();
    if (c.z() - threshold_m > 0.0) {
      const double rho = touchingDiscRadius(shape, threshold_m);
      box = Eigen::AlignedBox2d(c.head<2>() - Eigen::Vector2d::Constant(rho), c.head<2>() + Eigen::Vector2d::Constant(rho));
    }
  }
  return box;
}

// The x-interval of a row at height y that can hold candidates: within a ball's touching disc
// (centre `disc_centre`, radius `disc_radius`; none for other shapes: radius < 0) and not past a
// chart edge. Empty (lo > hi) where none can. Approximate to rounding, so the caller widens it by
// a texel, and tests a texel's point exactly (ChartBoundary::past) only within a texel of where
// an edge cuts the row (edge_lo, edge_hi), or everywhere where an edge runs nearly along the rows.
struct RowSpan {
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  double lo = -kInf, hi = kInf;
  double edge_lo = -kInf, edge_hi = kInf;
  bool test_every_texel = false;
};
RowSpan rowSpan(double y, const Eigen::Vector2d& disc_centre, double disc_radius, const ChartBoundary* boundary) {
  RowSpan r;
  if (boundary)
    for (std::size_t k = 0; k < boundary->count; ++k) {
      // Kept: normal . (x, y) <= offset. An edge nearly along x cuts whole rows or none: the
      // test of each texel decides them.
      const ChartEdge& e = boundary->edges[k];
      if (std::fabs(e.normal.x()) < 1e-6) {
        r.test_every_texel = true;
        continue;
      }
      const double x = (e.offset - e.normal.y() * y) / e.normal.x();
      if (e.normal.x() > 0.0) r.edge_hi = std::min(r.edge_hi, x);
      else r.edge_lo = std::max(r.edge_lo, x);
    }
  r.lo = r.edge_lo, r.hi = r.edge_hi;
  if (disc_radius >= 0.0) {
    const double dy = y - disc_centre.y();
    const double half = disc_radius * disc_radius - dy * dy;
    if (half < 0.0) return RowSpan{1.0, -1.0};
    r.lo = std::max(r.lo, disc_centre.x() - std::sqrt(half));
    r.hi = std::min(r.hi, disc_centre.x() + std::sqrt(half));
  }
  return r;
}

}  // namespace

FootprintTexels footprintTexels(const tex::TexturedSurface& surface, const Underside& shape, double threshold_m) {
  FootprintTexels f;
  const Eigen::AlignedBox3d bounds = planeBounds(shape);
  // The relief never rises above the plane (z <= 0): an object whose bottom is higher than the
  // threshold cannot touch it, whatever the texture holds.
  if (bounds.min().z() > threshold_m) return f;
  const Eigen::AlignedBox2d foot = touchingFootprint(shape, bounds, threshold_m);
  long long ia = 0, ja = 0, ib = 0, jb = 0;
  surface.texelContaining(foot.min().x(), foot.min().y(), ia, ja);
  surface.texelContaining(foot.max().x(), foot.max().y(), ib, jb);
  f.empty = false;
  f.i0 = std::min(ia, ib), f.i1 = std::max(ia, ib);
  f.j0 = std::min(ja, jb), f.j1 = std::max(ja, jb);
  const long long count = (f.i1 - f.i0 + 1) * (f.j1 - f.j0 + 1);
  if (count > kMaxFootprintTexels)
    f.stride_i = f.stride_j = (long long)std::ceil(std::sqrt(double(count) / double(kMaxFootprintTexels)));
  return f;
}

namespace {
// rasterizeRelief, compiled once with a textured box's surface read row by row (kBoxRows:
// textured_box_rows.hpp) and once without, so that the loop for every other object is the one
// it was (with the box's reader in the one loop, a ball with a bump map on the plain plane read
// 318-380 us a step against 285-373 in alternated runs: docs/physics.md, "What it costs").
template <bool kBoxRows>
RasterStats rasterize(const tex::TexturedSurface& surface, const Underside& shape, double threshold_m,
                      std::vector<ReliefCandidate>& out, const FaceTexture* object_texture, const GroundBend* bend,
                      bool normals, const ChartBoundary* boundary, double texture_within_m) {
  RasterStats stats;
  // Bent ground may rise above the plane under the object: the footprint reaches as high.
  double reach = 0.0;
  if (bend) {
    const Eigen::AlignedBox3d bounds = planeBounds(shape);
    reach = bend->highestOver(Eigen::AlignedBox2d(bounds.min().head<2>(), bounds.max().head<2>()));
  }
  const FootprintTexels f = footprintTexels(surface, shape, threshold_m + reach);
  if (f.empty) return stats;
  const long long i0 = f.i0, i1 = f.i1, j0 = f.j0, j1 = f.j1;
  stats.stride_i = f.stride_i, stats.stride_j = f.stride_j;

  // Texel centres step linearly with the (unwrapped) index: read the first one from the surface
  // (one place for the mapping convention), then step by the texel size; +i is +x, +j is -y.
  const tex::TextureMap& map = surface.map();
  const tex::Address address = surface.sampling().address;
  const Eigen::Vector2d texel = surface.mapping().texelSize(map);
  // A chart on a mesh whose uv squeezes the texture along one axis (a lathe near its pole: 32x at
  // the bowl's centre) reads the relief's envelope merged along it (mesh_relief_chart.cpp); what
  // is still squeezed (beyond the envelope's last level, or a relief without envelopes) is read at
  // the other axis's spacing along both. The squeezed features alias, and the contact's
  // resolution is the coarser axis's; read texel by texel, a 16 mm box at the bowl's centre
  // visited 83,000 texels a step.
  if (bend) {
    const double tx = std::fabs(texel.x()), ty = std::fabs(texel.y());
    if (2.0 * tx <= ty) stats.stride_i *= (long long)(ty / tx);
    else if (2.0 * ty <= tx) stats.stride_j *= (long long)(tx / ty);
  }
  const Eigen::Vector3d first = surface.texelPoint(i0, j0).q_local;
  const bool relief = surface.usesRelief();
  const bool textured = object_texture != nullptr &&
                        (shape.kind == Underside::Kind::Box || shape.kind == Underside::Kind::Sphere);
  std::optional<TexturedObjectSurface> object_surface;
  if (textured) object_surface.emplace(shape, *object_texture);
  // A textured box's surface read row by row (textured_box_rows.hpp).
  std::optional<TexturedBoxRows> box_rows;
  if constexpr (kBoxRows) box_rows.emplace(shape, *object_surface);
  TexturedBoxRows::Point box_point;
  // A ball's touching disc, as footprintTexels bounds it (its rows' texels beyond it cannot reach
  // the relief); the chart's edges.
  const Eigen::Vector3d centre = shape.plane_from_object.translation();
  const bool sphere = shape.kind == Underside::Kind::Sphere;
  // Where a ball's texture is read: within the threshold, or the tighter bound asked for.
  const double read_within = textured && sphere ? std::min(threshold_m, texture_within_m) : threshold_m;
  const double disc_radius = sphere ? touchingDiscRadius(shape, read_within + reach) : -1.0;
  const ChartBoundary* edges = boundary && boundary->count > 0 ? boundary : nullptr;
  const bool clipped = disc_radius >= 0.0 || edges != nullptr;
  for (long long j = j0; j <= j1; j += stats.stride_j) {
    const double y = first.y() - double(j - j0) * texel.y();
    const int rj = tex::resolveIndex(j, map.height(), address);
    if constexpr (kBoxRows) box_rows->startRow(y);
    long long row_i0 = i0, row_i1 = i1;
    RowSpan span;
    if (clipped) {
      span = rowSpan(y, centre.head<2>(), disc_radius, edges);
      if (span.lo > span.hi) continue;
      // The span in texel steps from the footprint's first, a texel wider either side; texels
      // off the footprint's stride grid are not its texels.
      const double a = (span.lo - first.x()) / texel.x(), b = (span.hi - first.x()) / texel.x();
      const double from = std::min(a, b) - 1.0, to = std::max(a, b) + 1.0;
      if (std::isfinite(from) && from > 0.0)
        row_i0 = std::min(i1 + 1, i0 + ((long long)std::ceil(from / double(stats.stride_i))) * stats.stride_i);
      if (std::isfinite(to) && to < double(i1 - i0)) row_i1 = std::max(i0 - 1, i0 + (long long)std::floor(to));
    }
    // Within a texel of an edge's cut, or on a row an edge runs along, each texel is tested.
    const double surely_from = span.edge_lo + std::fabs(texel.x()), surely_to = span.edge_hi - std::fabs(texel.x());
    // The texel's column in the map, stepped along the row (a wrapped map's index without a
    // division a texel; resolveIndex at the row's start).
    const bool wrap = address == tex::Address::Wrap;
    const int width = map.width();
    const int wrap_step = wrap ? int(stats.stride_i % width) : 0;
    const auto next_wrapped = [&](int k) { return k + wrap_step >= width ? k + wrap_step - width : k + wrap_step; };
    int wrapped_i = tex::resolveIndex(row_i0, width, address);
    for (long long i = row_i0; i <= row_i1; i += stats.stride_i, wrapped_i = next_wrapped(wrapped_i)) {
      ++stats.texels_visited;
      const double x = first.x() + double(i - i0) * texel.x();
      if (edges && (span.test_every_texel || !(x >= surely_from && x <= surely_to)) &&
          edges->past(Eigen::Vector3d(x, y, 0.0)))
        continue;
      std::optional<double> z;
      if constexpr (kBoxRows) {
        if (!box_rows->at(x, box_point)) continue;
        z = box_point.lowest_z;
      } else {
        z = sphere ? sphereLowestZ(centre, shape.radius, x, y) : lowestZ(shape, x, y);
        if (!z) continue;
      }
      const int ri = wrap ? wrapped_i : tex::resolveIndex(i, width, address);
      const double height = (relief ? -double(map.depth(ri, rj)) : 0.0) + (bend ? bend->height(x, y) : 0.0);
      auto ground = [&](const Eigen::Vector3d& n) { return bend ? bend->tilt(n, x, y) : n; };
      if (!textured) {
        const double depth = *z - height;
        if (depth < threshold_m)
          out.push_back({Eigen::Vector3d(x, y, height), normals ? ground(surface.texelNormal(i, j, ri, rj)) : kNoNormal,
                         depth, i, j});
        continue;
      }
      // An object's relief lies inside its smooth surface: where that is already beyond the
      // threshold, so is the relief, and its texture need not be read (most of a ball's footprint).
      if (*z - height >= threshold_m || *z - height > read_within) continue;
      double object_z = 0.0;
      if constexpr (kBoxRows) object_z = box_point.surface.z;
      else object_z = object_surface->zOver(x, y, *z);
      const double depth = object_z - height;
      if (depth >= threshold_m) continue;
      if (!normals) {
        out.push_back({Eigen::Vector3d(x, y, height), kNoNormal, depth, i, j});
        continue;
      }
      // The depth first: the object's normal is read only where the texel is a candidate (a
      // grooved block's groove floors, most of its face, lie beyond the threshold).
      Eigen::Vector3d n = ground(surface.texelNormal(i, j, ri, rj));
      std::optional<Eigen::Vector3d> up;
      if constexpr (kBoxRows) up = box_rows->nUp(box_point);
      else up = object_surface->over(x, y, *z).n_up;
      if (up) n = (n + *up).normalized();
      out.push_back({Eigen::Vector3d(x, y, height), n, depth, i, j});
    }
  }
  return stats;
}
}  // namespace

RasterStats rasterizeRelief(const tex::TexturedSurface& surface, const Underside& shape, double threshold_m,
                            std::vector<ReliefCandidate>& out, const FaceTexture* object_texture, const GroundBend* bend,
                            bool normals, const ChartBoundary* boundary, double texture_within_m) {
  if (object_texture && shape.kind == Underside::Kind::Box)
    return rasterize<true>(surface, shape, threshold_m, out, object_texture, bend, normals, boundary, texture_within_m);
  return rasterize<false>(surface, shape, threshold_m, out, object_texture, bend, normals, boundary, texture_within_m);
}

void withNormals(const tex::TexturedSurface& surface, const GroundBend* bend, const TexturedObjectSurface* object,
                 ReliefCandidate& c) {
  // The texel's data as rasterizeRelief resolves it (its stepped column equals resolveIndex's).
  const tex::Address address = surface.sampling().address;
  const int ri = tex::resolveIndex(c.i, surface.map().width(), address);
  const int rj = tex::resolveIndex(c.j, surface.map().height(), address);
  const Eigen::Vector3d n = surface.texelNormal(c.i, c.j, ri, rj);
  c.n_local = bend ? bend->tilt(n, c.p_surface.x(), c.p_surface.y()) : n;
  if (!object) return;
  const std::optional<ObjectSurfacePoint> p = object->at(c.p_surface.x(), c.p_surface.y());
  if (p && p->n_up) c.n_local = (c.n_local + *p->n_up).normalized();
}

namespace {
// A ball with a bump map's point farther than kRefineNearBorder from its texel's centre (in
// texels): the parabolas fitted again through it, each round through points half as far apart
// (from kRefineFirstSpan), at most kRefineRounds times (the last round's points 0.15 um apart on
// a 0.31 mm texel), until it moves less than kRefineSettled (3 nm there).
constexpr double kRefineNearBorder = 0.4;
constexpr double kRefineFirstSpan = 0.25;
constexpr int kRefineRounds = 10;
constexpr double kRefineSettled = 1e-5;
}  // namespace

ReliefCandidate refineDeepest(const tex::TexturedSurface& surface, const Underside& shape, const ReliefCandidate& c,
                              const GroundBend* bend, const FaceTexture* object_texture, bool settle_everywhere) {
  const Eigen::Vector2d texel = surface.mapping().texelSize(surface.map());
  auto raised = [&](double x, double y) { return bend ? bend->height(x, y) : 0.0; };
  std::optional<TexturedObjectSurface> object;
  if (object_texture) object.emplace(shape, *object_texture);
  // The object's surface over (x, y): its lowest point, pushed in by its relief if it has one.
  auto objectZ = [&](double x, double y) -> std::optional<double> {
    if (object) {
      const std::optional<ObjectSurfacePoint> p = object->at(x, y);
      return p ? std::optional<double>(p->z) : std::nullopt;
    }
    return lowestZ(shape, x, y);
  };
  // Depth at a neighbouring texel centre (di, dj texels away); NaN where the object is absent.
  auto depthAt = [&](int di, int dj) {
    const tex::TexelPoint t = surface.texelPoint(c.i + di, c.j + dj);
    const std::optional<double> z = objectZ(t.q_local.x(), t.q_local.y());
    return z ? *z - t.q_local.z() - raised(t.q_local.x(), t.q_local.y()) : std::nan("");
  };
  // Vertex of the parabola through (-1, m), (0, d0), (1, p), kept inside the texel.
  auto vertexThrough = [](double m, double d0, double p) {
    const double curvature = m + p - 2.0 * d0;
    if (!(curvature > 0.0)) return 0.0;  // flat, concave or a neighbour missing: stay put
    return std::clamp(0.5 * (m - p) / curvature, -0.5, 0.5);
  };
  auto vertex = [&](double m, double p) { return vertexThrough(m, c.depth, p); };
  double ox = vertex(depthAt(-1, 0), depthAt(1, 0));
  double oj = vertex(depthAt(0, -1), depthAt(0, 1));  // +j is -y
  if (ox == 0.0 && oj == 0.0) return c;
  if (object && (settle_everywhere || std::fabs(ox) > kRefineNearBorder || std::fabs(oj) > kRefineNearBorder)) {
    // A ball with a bump map whose point lies near its texel's border, where the basin's bottom
    // may be the neighbour's too: the parabolas fitted again through the point found, along each
    // axis in turn, through points closer each round, until it settles, so that either texel
    // gives one point. Fitted once through each texel's own centre lines, two texels tied in
    // depth either side of a basin's bottom on a groove's rounded rim (a kink of the bilinear
    // relief, which each line's parabola leans off by its own amount) gave points 13 µm apart
    // and 5 µm apart in depth by turns, and the grooved board's marble was kicked at 1.4 mm/s
    // each time (scenes/grooved_board.yaml, 2026-12-05). Every point refitted so, a bumpy ball
    // tip on tip, kept awake, rocked faster: 0.36 mm/s in its third second (the median of eight
    // starts) against 0.03 with the points near a border alone. The point stays within its texel.
    auto depthOff = [&](double dx, double dj) {
      const double x = c.p_surface.x() + dx * texel.x(), y = c.p_surface.y() - dj * texel.y();
      const std::optional<double> z = objectZ(x, y);
      return z ? *z - surface.at(x, y).height_m - raised(x, y) : std::nan("");
    };
    auto withinTexel = [](double o) { return std::clamp(o, -0.5, 0.5); };
    double h = kRefineFirstSpan;
    for (int round = 0; round < kRefineRounds; ++round, h *= 0.5) {
      const double nx = withinTexel(ox + h * vertexThrough(depthOff(ox - h, oj), depthOff(ox, oj), depthOff(ox + h, oj)));
      const double nj = withinTexel(oj + h * vertexThrough(depthOff(nx, oj - h), depthOff(nx, oj), depthOff(nx, oj + h)));
      const bool settled = std::fabs(nx - ox) < kRefineSettled && std::fabs(nj - oj) < kRefineSettled;
      ox = nx, oj = nj;
      if (settled) break;
    }
  }
  const double x = c.p_surface.x() + ox * texel.x(), y = c.p_surface.y() - oj * texel.y();
  const std::optional<ObjectSurfacePoint> on_object =
      object ? object->at(x, y) : std::optional<ObjectSurfacePoint>();
  const std::optional<double> z = object ? (on_object ? std::optional<double>(on_object->z) : std::nullopt)
                                         : lowestZ(shape, x, y);
  if (!z) return c;
  const tex::SurfacePoint s = surface.at(x, y);
  const double height = s.height_m + raised(x, y);
  ReliefCandidate r = c;
  r.p_surface = Eigen::Vector3d(x, y, height);
  r.n_local = bend ? bend->tilt(s.n_local, x, y) : s.n_local;
  if (on_object && on_object->n_up) r.n_local = (r.n_local + *on_object->n_up).normalized();
  r.depth = *z - height;
  return r;
}

namespace {
// The relief's point under (x, y) (bilinear, raised by `bend`) as a contact candidate for an
// object whose underside there lies at `object_z`: its texel, its normal, the gap between the two.
ReliefCandidate candidateUnder(const tex::TexturedSurface& surface, const GroundBend* bend, double x, double y,
                               double object_z) {
  const tex::SurfacePoint s = surface.at(x, y);
  const double raise = bend ? bend->height(x, y) : 0.0;
  ReliefCandidate r;
  r.p_surface = Eigen::Vector3d(x, y, s.height_m + raise);
  r.n_local = bend ? bend->tilt(s.n_local, x, y) : s.n_local;
  r.depth = object_z - s.height_m - raise;
  surface.texelContaining(x, y, r.i, r.j);
  return r;
}
}  // namespace

std::optional<ReliefCandidate> deepestBetweenTexelCentres(const tex::TexturedSurface& surface, const Underside& ball,
                                                          const GroundBend* bend, double threshold_m) {
  constexpr double kOpen = std::numeric_limits<double>::infinity();  // no sphere over the point
  // Spans from a texel down to a hundred-thousandth of one (20 nm on 2 mm texels); a span is
  // halved once no move along either axis brings the two closer, so the search always ends.
  constexpr double kSmallestSpan = 1e-5;
  constexpr int kMostRounds = 64;
  auto depthAt = [&](const Eigen::Vector2d& q) {
    const std::optional<double> z = lowestZ(ball, q.x(), q.y());
    return z ? *z - surface.at(q.x(), q.y()).height_m - (bend ? bend->height(q.x(), q.y()) : 0.0) : kOpen;
  };
  // The relief lies at or under its plane, raised by no more than the bend rises under the ball:
  // a ball higher than that over it by the threshold touches nothing (a ball in the air above the
  // plane, every step).
  const Eigen::AlignedBox3d bounds = planeBounds(ball);
  const Eigen::AlignedBox2d footprint(bounds.min().head<2>(), bounds.max().head<2>());
  if (bounds.min().z() - (bend ? bend->highestOver(footprint) : 0.0) > threshold_m) return std::nullopt;
  const Eigen::Vector2d texel = surface.mapping().texelSize(surface.map()).cwiseAbs();
  Eigen::Vector2d at = ball.plane_from_object.translation().head<2>();
  double depth = depthAt(at);
  double span = 1.0;  // in texels
  for (int round = 0; round < kMostRounds && span >= kSmallestSpan; ++round) {
    bool moved = false;
    for (int axis = 0; axis < 2; ++axis) {
      Eigen::Vector2d step = Eigen::Vector2d::Zero();
      step[axis] = span * texel[axis];
      const double before = depthAt(at - step), after = depthAt(at + step);
      // The parabola's vertex through the three, no farther than the span; towards the closer
      // side where they do not curve up (an open side counts as farthest).
      const double curvature = before + after - 2.0 * depth;
      double t = 0.0;
      if (std::isfinite(curvature) && curvature > 0.0) {
        t = std::clamp(0.5 * (before - after) / curvature, -1.0, 1.0);
      } else if (before < depth || after < depth) {
        t = before < after ? -1.0 : 1.0;
      }
      if (t == 0.0) continue;
      const Eigen::Vector2d next = at + t * step;
      const double there = depthAt(next);
      if (there < depth) at = next, depth = there, moved = true;
    }
    if (!moved) span *= 0.5;
  }
  if (!(depth <= threshold_m)) return std::nullopt;
  return candidateUnder(surface, bend, at.x(), at.y(), *lowestZ(ball, at.x(), at.y()));
}

bool boxUnderTwoTexelsAcross(const tex::TexturedSurface& surface, const Underside& box) {
  const Eigen::Vector3d across = planeBounds(box).sizes();
  const Eigen::Vector2d texel = surface.mapping().texelSize(surface.map()).cwiseAbs();
  return across.x() < 2.0 * texel.x() || across.y() < 2.0 * texel.y();
}

std::size_t boxCornerContacts(const tex::TexturedSurface& surface, const Underside& box, const GroundBend* bend,
                              double threshold_m, std::span<const ReliefCandidate> centres,
                              std::array<ReliefCandidate, kMaxReliefContacts>& out) {
  // As for a ball: a box higher over the plane than the bend rises under it, by the threshold,
  // touches nothing.
  const Eigen::AlignedBox3d bounds = planeBounds(box);
  const Eigen::AlignedBox2d footprint(bounds.min().head<2>(), bounds.max().head<2>());
  if (bounds.min().z() - (bend ? bend->highestOver(footprint) : 0.0) > threshold_m) return 0;
  std::array<Eigen::Vector3d, 8> corners;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d sign(k & 1 ? 1.0 : -1.0, k & 2 ? 1.0 : -1.0, k & 4 ? 1.0 : -1.0);
    corners[std::size_t(k)] = box.plane_from_object * sign.cwiseProduct(box.half_extents);
  }
  std::sort(corners.begin(), corners.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a.z() < b.z(); });
  std::size_t n = 0;
  double deepest_corner = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < 4; ++k) {
    const ReliefCandidate r = candidateUnder(surface, bend, corners[k].x(), corners[k].y(), corners[k].z());
    if (!(r.depth <= threshold_m)) continue;
    out[n++] = r;
    deepest_corner = std::min(deepest_corner, r.depth);
  }
  // A centre's contact where it lies deeper than every corner (a bump under the box), in place of
  // the shallowest corner once all four are kept.
  constexpr double kDeeperThanCorners = 1e-6;
  for (const ReliefCandidate& c : centres) {
    if (!(c.depth < deepest_corner - kDeeperThanCorners)) continue;
    if (n < out.size()) {
      out[n++] = c;
      continue;
    }
    std::size_t shallowest = 0;
    for (std::size_t m = 1; m < n; ++m) shallowest = out[m].depth > out[shallowest].depth ? m : shallowest;
    out[shallowest] = c;
  }
  return n;
}

}  // namespace thx::phys
