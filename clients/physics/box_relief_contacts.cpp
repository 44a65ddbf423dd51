#include "clients/physics/box_relief_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

namespace thx::phys {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// A face pair whose normal is this close to level bounds no z (underside.cpp's rule).
constexpr double kParallel = 1e-12;

// One pair of the box's opposite faces along the current row of texel centres (plane frame,
// y fixed): where a vertical line at x enters and leaves the slab between them,
// lo(x) = a_lo + b x and hi(x) = a_hi + b x. A slab whose faces stand vertical bounds no z
// (a_lo = -inf, a_hi = +inf, b = 0) but x: |s_row + ux x| <= h, an interval of the row.
struct RowSlab {
  double a_lo = 0.0, a_hi = 0.0, b = 0.0;
  bool vertical = false;
  double s_row = 0.0, ux = 0.0, h = 0.0;
};

struct BoxSlabs {
  Eigen::Vector3d centre;
  std::array<Eigen::Vector3d, 3> axes;
  Eigen::Vector3d half;

  explicit BoxSlabs(const Underside& box)
      : centre(box.plane_from_object.translation()), half(box.half_extents) {
    for (int k = 0; k < 3; ++k) axes[std::size_t(k)] = box.plane_from_object.linear().col(k);
  }
  // The slabs along the row at y. The coordinate along axis u of (x, y, 0) is s_row + ux x.
  std::array<RowSlab, 3> row(double y) const {
    std::array<RowSlab, 3> slabs;
    for (std::size_t k = 0; k < 3; ++k) {
      const Eigen::Vector3d& u = axes[k];
      RowSlab& s = slabs[k];
      s.h = half[Eigen::Index(k)];
      s.ux = u.x();
      s.s_row = (y - centre.y()) * u.y() - centre.z() * u.z() - centre.x() * u.x();
      s.vertical = std::fabs(u.z()) < kParallel;
      if (s.vertical) {
        s.a_lo = -kInf, s.a_hi = kInf, s.b = 0.0;
        continue;
      }
      // Along the line the coordinate changes by u.z per metre of z: it enters the slab at the
      // face its normal turns down to.
      const double enter = u.z() > 0.0 ? -s.h : s.h;
      s.a_lo = (enter - s.s_row) / u.z();
      s.a_hi = (-enter - s.s_row) / u.z();
      s.b = -u.x() / u.z();
    }
    return slabs;
  }
};

// The columns [first, last] of a row whose texel centres (x = x0 + gi dx) lie within every
// vertical slab; empty (first > last) where none does.
void clipToVerticalSlabs(const std::array<RowSlab, 3>& row, double x0, double dx, long long& first, long long& last) {
  for (const RowSlab& s : row) {
    if (!s.vertical) continue;
    // |s_row + ux (x0 + gi dx)| <= h, i.e. -h <= s_row + ux x0 + (ux dx) gi <= h.
    const double c0 = s.s_row + s.ux * x0, c1 = s.ux * dx;
    if (c1 == 0.0) {
      if (std::fabs(c0) > s.h) first = 1, last = 0;
      continue;
    }
    double g_a = (-s.h - c0) / c1, g_b = (s.h - c0) / c1;
    if (g_a > g_b) std::swap(g_a, g_b);
    first = std::max(first, (long long)std::ceil(std::max(g_a, -1.0)));
    last = std::min(last, (long long)std::floor(std::min(g_b, double(last) + 1.0)));
  }
}

// A touching texel kept for the selection: a row run's end or the deepest.
ReliefCandidate keptTexel(long long i, long long j, double x, double y, double height, double depth) {
  ReliefCandidate c;
  c.p_surface = Eigen::Vector3d(x, y, height);
  c.depth = depth;
  c.i = i;
  c.j = j;
  return c;
}

bool scanOrderBefore(const ReliefCandidate& a, const ReliefCandidate& b) {
  return a.j != b.j ? a.j < b.j : a.i < b.i;
}

}  // namespace

bool boxReliefContacts(const tex::TexturedSurface& surface, const Underside& box, double threshold_m,
                       ChosenReliefContacts& out) {
  out = ChosenReliefContacts{};
  const FootprintTexels f = footprintTexels(surface, box, threshold_m);
  if (f.empty) return true;
  if (f.stride != 1) return false;
  const long long ni = f.i1 - f.i0 + 1, nj = f.j1 - f.j0 + 1;
  out.raster.texels_visited = ni * nj;

  const tex::TextureMap& map = surface.map();
  const tex::Address address = surface.sampling().address;
  const Eigen::Vector2d texel = surface.mapping().texelSize(map);
  // The first texel centre from the surface (one place for the mapping convention), the others
  // stepped from it exactly as rasterizeRelief steps them: the same coordinates to the bit.
  const Eigen::Vector3d first = surface.texelPoint(f.i0, f.j0).q_local;
  const bool relief = surface.usesRelief();

  // Reused between steps: a resting box costs no allocation per step.
  thread_local std::vector<double> depth;  // per footprint texel; +inf where it does not touch
  thread_local std::vector<int> columns;   // resolved column of each footprint column
  thread_local std::vector<ReliefCandidate> kept;
  depth.assign(std::size_t(ni * nj), kInf);
  columns.resize(std::size_t(ni));
  for (long long gi = 0; gi < ni; ++gi) columns[std::size_t(gi)] = tex::resolveIndex(f.i0 + gi, map.width(), address);
  kept.clear();

  const BoxSlabs slabs(box);
  double deepest = kInf;
  long long deepest_cell = -1;
  for (long long gj = 0; gj < nj; ++gj) {
    const double y = first.y() - double(gj) * texel.y();
    const long long j = f.j0 + gj;
    const int rj = tex::resolveIndex(j, map.height(), address);
    const std::array<RowSlab, 3> row = slabs.row(y);
    double* const depth_row = depth.data() + gj * ni;
    // The row's depths first (a tight loop, no branch on the data), then its runs.
    long long first_col = 0, last_col = ni - 1;
    clipToVerticalSlabs(row, first.x(), texel.x(), first_col, last_col);
    const int* const column = columns.data();
    for (long long gi = first_col; gi <= last_col; ++gi) {
      const double x = first.x() + double(gi) * texel.x();
      const double lo = std::max(std::max(row[0].a_lo + row[0].b * x, row[1].a_lo + row[1].b * x),
                                 row[2].a_lo + row[2].b * x);
      const double hi = std::min(std::min(row[0].a_hi + row[0].b * x, row[1].a_hi + row[1].b * x),
                                 row[2].a_hi + row[2].b * x);
      const double height = relief ? -double(map.depth(column[gi], rj)) : 0.0;
      const double d = lo - height;
      depth_row[gi] = lo <= hi && d < threshold_m ? d : kInf;
    }
    auto keep = [&](long long gi) {
      const double height = relief ? -double(map.depth(columns[std::size_t(gi)], rj)) : 0.0;
      kept.push_back(keptTexel(f.i0 + gi, j, first.x() + double(gi) * texel.x(), y, height, depth_row[gi]));
    };
    long long run_start = -1;
    for (long long gi = 0; gi <= ni; ++gi) {
      const bool touches = gi < ni && depth_row[gi] < kInf;
      if (touches) {
        if (run_start < 0) run_start = gi;
        if (depth_row[gi] < deepest) deepest = depth_row[gi], deepest_cell = gj * ni + gi;
      } else if (run_start >= 0) {
        keep(run_start);
        if (gi - 1 != run_start) keep(gi - 1);
        run_start = -1;
      }
    }
  }
  if (kept.empty()) return true;
  // The deepest texel joins the runs' ends in scan order, so that among equally deep texels the
  // selection takes the first in scan order, as the general rule does.
  {
    const long long gi = deepest_cell % ni, gj = deepest_cell / ni;
    const long long j = f.j0 + gj;
    const double height =
        relief ? -double(map.depth(columns[std::size_t(gi)], tex::resolveIndex(j, map.height(), address))) : 0.0;
    const ReliefCandidate deepest_texel = keptTexel(f.i0 + gi, j, first.x() + double(gi) * texel.x(),
                                                    first.y() - double(gj) * texel.y(), height, deepest);
    const auto at = std::lower_bound(kept.begin(), kept.end(), deepest_texel, scanOrderBefore);
    if (at == kept.end() || at->i != deepest_texel.i || at->j != deepest_texel.j) kept.insert(at, deepest_texel);
  }

  std::array<std::size_t, kMaxReliefContacts> chosen{};
  const std::size_t n = selectReliefContacts(kept, chosen);

  // snapToBasins on the depth grid: each chosen texel walks to its lowest neighbour (8 around,
  // the first of equals in scan order) while that is deeper; it moves there unless an earlier
  // chosen texel ended in the same place.
  std::array<long long, kMaxReliefContacts> cell{};
  for (std::size_t c = 0; c < n; ++c) {
    long long gi = kept[chosen[c]].i - f.i0, gj = kept[chosen[c]].j - f.j0;
    for (;;) {
      long long next_i = gi, next_j = gj;
      double next_depth = depth[std::size_t(gj * ni + gi)];
      for (long long dj = -1; dj <= 1; ++dj)
        for (long long di = -1; di <= 1; ++di) {
          const long long a = gi + di, b = gj + dj;
          if (a < 0 || b < 0 || a >= ni || b >= nj) continue;
          const double v = depth[std::size_t(b * ni + a)];
          if (v < next_depth) next_i = a, next_j = b, next_depth = v;
        }
      if (next_i == gi && next_j == gj) break;
      gi = next_i, gj = next_j;
    }
    const long long here = gj * ni + gi;
    const bool taken = std::find(cell.begin(), cell.begin() + std::ptrdiff_t(c), here) != cell.begin() + std::ptrdiff_t(c);
    cell[c] = taken ? (kept[chosen[c]].j - f.j0) * ni + (kept[chosen[c]].i - f.i0) : here;
  }

  for (std::size_t c = 0; c < n; ++c) {
    const long long gi = cell[c] % ni, gj = cell[c] / ni;
    const long long i = f.i0 + gi, j = f.j0 + gj;
    const int ri = columns[std::size_t(gi)], rj = tex::resolveIndex(j, map.height(), address);
    const double height = relief ? -double(map.depth(ri, rj)) : 0.0;
    ReliefCandidate& contact = out.contacts[c];
    contact = keptTexel(i, j, first.x() + double(gi) * texel.x(), first.y() - double(gj) * texel.y(), height,
                        depth[std::size_t(cell[c])]);
    contact.n_local = surface.texelNormal(i, j, ri, rj);
  }
  out.count = n;
  return true;
}

ChosenReliefContacts generalBoxReliefContacts(const tex::TexturedSurface& surface, const Underside& box,
                                              double threshold_m) {
  ChosenReliefContacts out;
  std::vector<ReliefCandidate> candidates;
  out.raster = rasterizeRelief(surface, box, threshold_m, candidates);
  std::array<std::size_t, kMaxReliefContacts> chosen{};
  out.count = selectReliefContacts(candidates, chosen);
  snapToBasins(candidates, out.raster.stride, std::span(chosen.data(), out.count));
  for (std::size_t c = 0; c < out.count; ++c) out.contacts[c] = candidates[chosen[c]];
  return out;
}

}  // namespace thx::phys
