#include "server/capsule_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thx::srv {

namespace {

// Keeps the kMaxToolContacts nearest: a full list gives up its farthest for a nearer one.
void offer(ToolContacts& out, const ToolContact& contact) {
  if (out.count < kMaxToolContacts) {
    out.c[std::size_t(out.count++)] = contact;
    return;
  }
  out.overflow = true;
  int farthest = 0;
  for (int k = 1; k < out.count; ++k)
    if (out.c[std::size_t(k)].gap_m > out.c[std::size_t(farthest)].gap_m) farthest = k;
  if (contact.gap_m < out.c[std::size_t(farthest)].gap_m) out.c[std::size_t(farthest)] = contact;
}

// The parameter interval of the segment whose points lie at or below height z_max.
bool partBelow(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double z_max, double& t0, double& t1) {
  t0 = 0.0;
  t1 = 1.0;
  const double dz = b.z() - a.z();
  if (std::abs(dz) < 1e-15) return a.z() <= z_max;
  const double t_cross = (z_max - a.z()) / dz;
  if (dz > 0.0)
    t1 = std::min(1.0, t_cross);
  else
    t0 = std::max(0.0, t_cross);
  return t0 <= t1;
}

// The parameter interval of [t0, t1] whose x lies in [x_lo, x_hi].
bool partInSlab(double ax, double bx, double x_lo, double x_hi, double& t0, double& t1) {
  const double dx = bx - ax;
  if (std::abs(dx) < 1e-15) return ax >= x_lo && ax <= x_hi;
  double ta = (x_lo - ax) / dx;
  double tb = (x_hi - ax) / dx;
  if (ta > tb) std::swap(ta, tb);
  t0 = std::max(t0, ta);
  t1 = std::min(t1, tb);
  return t0 <= t1;
}

// A texel centre's squared distance to the capsule's axis (no square root: the search compares
// distances, and takes the root only of the nearest), and which part of the capsule is nearest:
// the tip's ball (0), the shaft (1) or the back end's ball (2).
struct Nearness {
  double d2 = 0.0;
  int part = 1;
};

// What nearness() needs, worked out once a search: the texel grid on the plane and the axis.
struct SearchGrid {
  const tex::TextureMap* map = nullptr;
  tex::Address address = tex::Address::Wrap;
  bool relief = false;
  double x_first = 0.0, dx = 0.0;  // texel i's centre x = x_first + i dx
  double y_first = 0.0, dy = 0.0;  // texel j's centre y = y_first - j dy (rows run down the image)
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), ab = Eigen::Vector3d::Zero();
  double inv_len2 = 0.0;  // 0 for a ball (a == b)

  SearchGrid(const tex::TexturedSurface& surface, const CapsuleShape& cap)
      : map(&surface.map()), address(surface.sampling().address), relief(surface.usesRelief()), a(cap.a),
        ab(cap.b - cap.a) {
    const Eigen::Vector2d size = surface.mapping().size_m;
    dx = size.x() / map->width();
    dy = size.y() / map->height();
    x_first = 0.5 * dx - 0.5 * size.x();
    y_first = 0.5 * size.y() - 0.5 * dy;
    const double len2 = ab.squaredNorm();
    inv_len2 = len2 > 1e-30 ? 1.0 / len2 : 0.0;
  }
};

Nearness nearness(const SearchGrid& g, long long i, long long j) {
  const double depth = g.relief ? double(g.map->depth(tex::resolveIndex(i, g.map->width(), g.address),
                                                      tex::resolveIndex(j, g.map->height(), g.address)))
                                : 0.0;
  const Eigen::Vector3d q(g.x_first + double(i) * g.dx, g.y_first - double(j) * g.dy, -depth);
  const double t = (q - g.a).dot(g.ab) * g.inv_len2;
  Nearness n;
  n.part = t <= 0.0 ? 0 : (t >= 1.0 ? 2 : 1);
  n.d2 = (g.a + std::clamp(t, 0.0, 1.0) * g.ab - q).squaredNorm();
  return n;
}

// Texel (i, j) is where the capsule's part comes nearest this patch of the surface: no
// 8-neighbour nearest to the same part is nearer, and of equal ones it is the first in row order.
// One contact per feature (a crest under the shaft, each wall of a valley under the ball) instead
// of every texel within reach: the constraints stay few and far from parallel, which is what the
// solver's convergence needs.
bool nearestOfItsPatch(const SearchGrid& g, long long i, long long j, const Nearness& here) {
  for (int dj = -1; dj <= 1; ++dj)
    for (int di = -1; di <= 1; ++di) {
      if (di == 0 && dj == 0) continue;
      const Nearness n = nearness(g, i + di, j + dj);
      if (n.part != here.part) continue;
      if (n.d2 < here.d2) return false;
      if (n.d2 == here.d2 && (dj < 0 || (dj == 0 && di < 0))) return false;
    }
  return true;
}

// The contact at texel (i, j), if it has one. Where the texture is smooth around it (its
// 4-neighbours' normals within kCreaseCos of its own), the texel's plane (its centre, its own
// normal), as the point pen's plane proxies: the texture's normal is the contact's. At a crease (a
// crest, a valley floor, a brick's edge) a plane would reach over the neighbouring wall (a crest's
// level plane lifts a ball out of the valley beside it), so the contact is the point itself: its
// normal from the point to the capsule's nearest axis point (from the crease's line where the
// crease runs along x or y), its gap that distance less the radius. A smooth texel whose plane the axis is behind is the far side of a crest (no contact),
// unless the axis is under that very texel (pushed through it: the plane pushes it back out).
bool texelContact(const tex::TexturedSurface& surface, const CapsuleShape& cap, long long i, long long j,
                  ToolContact& contact) {
  contact.has_texel = true;
  contact.texel_i = i;
  contact.texel_j = j;
  constexpr double kCreaseCos = 0.990268;  // 8 degrees, the point pen's crease angle (RendererConfig)
  const tex::TexelPoint p = surface.texelPoint(i, j);
  const Eigen::Vector3d s = cap.a + nearestOnSegment(cap.a, cap.b, p.q_local) * (cap.b - cap.a);
  auto alike = [&](int di, int dj) { return surface.texelPoint(i + di, j + dj).n_local.dot(p.n_local) >= kCreaseCos; };
  const bool along_x = alike(1, 0) && alike(-1, 0);
  const bool along_y = alike(0, 1) && alike(0, -1);
  const bool smooth = along_x && along_y;
  Eigen::Vector3d to_axis = s - p.q_local;
  const double above = p.n_local.dot(to_axis);
  // A crease that runs along x or y (a crest, a groove's floor, a brick's edge) is a line through
  // the point: its normal has no part along the line, or a shaft crossing a crest between two
  // texel centres would be pushed along the crest by the nearer one. Elsewhere (a corner) a point.
  if (!smooth && along_x != along_y) to_axis -= to_axis.dot(along_x ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()) *
                                                (along_x ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY());
  const double distance = to_axis.norm();
  if (!smooth && distance > 1e-12) {
    contact.normal = to_axis / distance;
    contact.point = p.q_local;
    contact.gap_m = distance - cap.radius_m;
    return true;
  }
  if (above < 0.0 && (s - p.q_local).head<2>().norm() > surface.texelSize()) return false;
  contact.normal = p.n_local;
  contact.point = s - above * p.n_local;
  contact.gap_m = above - cap.radius_m;
  return true;
}

void reliefContacts(const tex::TexturedSurface& surface, const CapsuleShape& cap, double margin_m, double t0,
                    double t1, bool contacts_wanted, const ReliefBlockHeights* blocks, ToolContacts& out) {
  constexpr int kBlock = ReliefBlockHeights::kBlock;
  const bool skipping = blocks != nullptr && !blocks->empty();
  const SearchGrid grid(surface, cap);
  double nearest_d2 = std::numeric_limits<double>::infinity();
  const double reach2 = (cap.radius_m + margin_m) * (cap.radius_m + margin_m);
  const double reach = cap.radius_m + margin_m;
  const Eigen::Vector3d lo = cap.a + t0 * (cap.b - cap.a);
  const Eigen::Vector3d hi = cap.a + t1 * (cap.b - cap.a);
  // Every texel lies at or below z = 0, so a texel within reach of an axis point at height h > 0
  // is within sqrt(reach² - h²) of it across the plane: a pen resting on the surface searches a
  // disc about half its radius wide, not its whole radius.
  auto across = [&](double h) { return h > 0.0 ? std::sqrt(std::max(0.0, reach2 - h * h)) : reach; };
  const double reach_across = across(std::min(lo.z(), hi.z()));
  long long i_first = 0, j_first = 0, i_last = 0, j_last = 0;
  surface.texelContaining(std::min(lo.x(), hi.x()) - reach_across, std::max(lo.y(), hi.y()) + reach_across, i_first,
                          j_first);
  surface.texelContaining(std::max(lo.x(), hi.x()) + reach_across, std::min(lo.y(), hi.y()) - reach_across, i_last,
                          j_last);
  const Eigen::Vector2d texel = surface.mapping().texelSize(surface.map());
  for (long long i = i_first; i <= i_last; ++i) {
    // The shaft's part over this column of texels (widened by the reach), and its y span.
    const double x_centre = surface.texelCentre(i, j_first).x();
    double s0 = t0, s1 = t1;
    if (!partInSlab(cap.a.x(), cap.b.x(), x_centre - reach_across - 0.5 * texel.x(),
                    x_centre + reach_across + 0.5 * texel.x(), s0, s1))
      continue;
    // The shaft's lowest axis point over this column: it bounds the span across, and a block
    // whose top is farther below it than the radius and the margin holds nothing within reach.
    const double axis_low = std::min(cap.a.z() + s0 * (cap.b.z() - cap.a.z()), cap.a.z() + s1 * (cap.b.z() - cap.a.z()));
    const double column_across = across(axis_low);
    const double y0 = cap.a.y() + s0 * (cap.b.y() - cap.a.y());
    const double y1 = cap.a.y() + s1 * (cap.b.y() - cap.a.y());
    long long ignored = 0, j_top = 0, j_bottom = 0;
    surface.texelContaining(x_centre, std::max(y0, y1) + column_across, ignored, j_top);
    surface.texelContaining(x_centre, std::min(y0, y1) - column_across, ignored, j_bottom);
    const long long bi = (long long)std::floor(double(i) / kBlock);
    for (long long j = std::max(j_top, j_first); j <= std::min(j_bottom, j_last); ++j) {
      if (skipping) {
        const long long bj = (long long)std::floor(double(j) / kBlock);
        if (axis_low - reach > blocks->top(surface, bi, bj)) {
          j = (bj + 1) * kBlock - 1;  // the block's last row; the loop steps past it
          continue;
        }
      }
      ++out.texels_examined;
      const Nearness here = nearness(grid, i, j);
      nearest_d2 = std::min(nearest_d2, here.d2);
      if (here.d2 >= reach2 || !contacts_wanted) continue;
      if (!nearestOfItsPatch(grid, i, j, here)) continue;
      ToolContact contact;
      if (texelContact(surface, cap, i, j, contact) && contact.gap_m < margin_m) offer(out, contact);
    }
  }
  if (nearest_d2 < std::numeric_limits<double>::infinity())
    out.nearest_gap_m = std::min(out.nearest_gap_m, std::sqrt(nearest_d2) - cap.radius_m);
}

// A normal map: the flat plane, each texel's plane through (x, y, 0) with the sampled normal, read
// under the shaft's line. Kept: the ends of the part within reach (so a shaft lying flat rests on
// both), and every sample nearer than both of its neighbours (the first of equal ones).
void normalMapContacts(const tex::TexturedSurface& surface, const CapsuleShape& cap, double margin_m, double t0,
                       double t1, bool contacts_wanted, ToolContacts& out) {
  const Eigen::Vector2d ab_xy = (cap.b - cap.a).head<2>();
  const double step = 0.5 * surface.texelSize();
  constexpr int kMaxSamples = 4096;
  const int samples = std::clamp(int(std::ceil(ab_xy.norm() * (t1 - t0) / step)) + 1, 1, kMaxSamples);
  auto contactAt = [&](int k) {
    const double t = samples == 1 ? t0 : t0 + (t1 - t0) * double(k) / double(samples - 1);
    const Eigen::Vector3d s = cap.a + t * (cap.b - cap.a);
    ++out.texels_examined;
    const tex::SurfacePoint sp = surface.at(s.x(), s.y());
    const double above = sp.n_local.dot(s - Eigen::Vector3d(s.x(), s.y(), 0.0));
    ToolContact contact;
    contact.normal = sp.n_local;
    contact.point = s - above * sp.n_local;
    contact.gap_m = above - cap.radius_m;
    out.nearest_gap_m = std::min(out.nearest_gap_m, contact.gap_m);
    return contact;
  };
  constexpr double kFar = std::numeric_limits<double>::infinity();
  ToolContact current = contactAt(0);
  double previous_gap = kFar;
  for (int k = 0; k < samples; ++k) {
    const ToolContact next = k + 1 < samples ? contactAt(k + 1) : ToolContact{};
    const double next_gap = k + 1 < samples ? next.gap_m : kFar;
    const bool end = k == 0 || k + 1 == samples;
    const bool nearest = current.gap_m < previous_gap && current.gap_m <= next_gap;
    if (contacts_wanted && current.gap_m < margin_m && (end || nearest)) offer(out, current);
    previous_gap = current.gap_m;
    current = next;
  }
}

}  // namespace

double nearestOnSegment(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& p) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 < 1e-30) return 0.0;
  return std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
}

namespace {

void search(const tex::TexturedSurface& surface, const CapsuleShape& capsule, double margin_m, bool contacts_wanted,
            const ReliefBlockHeights* blocks, ToolContacts& out) {
  out.count = 0;
  out.texels_examined = 0;
  out.overflow = false;
  out.nearest_gap_m = std::numeric_limits<double>::infinity();
  // The surface lies at or below z = 0: only the part of the shaft within reach of that matters.
  double t0 = 0.0, t1 = 1.0;
  if (!partBelow(capsule.a, capsule.b, capsule.radius_m + margin_m, t0, t1)) return;
  if (surface.usesRelief())
    reliefContacts(surface, capsule, margin_m, t0, t1, contacts_wanted, blocks, out);
  else
    normalMapContacts(surface, capsule, margin_m, t0, t1, contacts_wanted, out);
}

}  // namespace

void findCapsuleContacts(const tex::TexturedSurface& surface, const CapsuleShape& capsule, double margin_m,
                         ToolContacts& out, const ReliefBlockHeights* blocks) {
  search(surface, capsule, margin_m, true, blocks, out);
}

void findCapsuleClearance(const tex::TexturedSurface& surface, const CapsuleShape& capsule, double margin_m,
                          ToolContacts& out, const ReliefBlockHeights* blocks) {
  search(surface, capsule, margin_m, false, blocks, out);
}

ReliefBlockHeights::ReliefBlockHeights(const tex::TexturedSurface& surface) {
  const tex::TextureMap& map = surface.map();
  if (!surface.usesRelief() || map.width() % kBlock != 0 || map.height() % kBlock != 0) return;
  blocks_x_ = map.width() / kBlock;
  const int blocks_y = map.height() / kBlock;
  top_m_.assign(std::size_t(blocks_x_) * std::size_t(blocks_y), -std::numeric_limits<float>::infinity());
  for (int j = 0; j < map.height(); ++j)
    for (int i = 0; i < map.width(); ++i) {
      float& top = top_m_[std::size_t(j / kBlock) * std::size_t(blocks_x_) + std::size_t(i / kBlock)];
      top = std::max(top, -map.depth(i, j));
    }
}

double ReliefBlockHeights::top(const tex::TexturedSurface& surface, long long bi, long long bj) const {
  // Every unwrapped texel of the block resolves into one stored block: with wrap, the sides are
  // multiples of kBlock; with clamp, the texels beyond an edge are the edge's.
  const tex::TextureMap& map = surface.map();
  const tex::Address address = surface.sampling().address;
  const int ri = tex::resolveIndex(bi * kBlock, map.width(), address) / kBlock;
  const int rj = tex::resolveIndex(bj * kBlock, map.height(), address) / kBlock;
  return double(top_m_[std::size_t(rj) * std::size_t(blocks_x_) + std::size_t(ri)]);
}

constexpr double kCarriedPlaneTexels = 1.5;

void addCarriedContact(const tex::TexturedSurface& surface, const CapsuleShape& capsule, long long i, long long j,
                       ToolContacts& out) {
  for (int k = 0; k < out.count; ++k) {
    const ToolContact& c = out.c[std::size_t(k)];
    if (c.has_texel && c.texel_i == i && c.texel_j == j) return;
  }
  // A texel's plane stands for the surface only near the texel: one the tool has left behind (the
  // axis more than its radius and two texels away across the plane) is not carried.
  const Eigen::Vector3d q = surface.texelCentre(i, j);
  const Eigen::Vector3d s = capsule.a + nearestOnSegment(capsule.a, capsule.b, q) * (capsule.b - capsule.a);
  if ((s - q).head<2>().norm() > capsule.radius_m + 2.0 * surface.texelSize()) return;
  ToolContact contact;
  if (!texelContact(surface, capsule, i, j, contact)) return;
  // A smooth texel's plane is the surface only over the texel and its edge: carried beyond that (a
  // ball gone over a crest) it would hold the tool above the far side.
  if ((contact.point - q).head<2>().norm() > kCarriedPlaneTexels * surface.texelSize()) return;
  offer(out, contact);
}

}  // namespace thx::srv
