#include "clients/physics/box_relief_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <vector>

namespace thx::phys {

namespace {

constexpr double kUnbounded = std::numeric_limits<double>::infinity();

// One pair of the box's opposite faces along the current row of texel centres (plane frame,
// y fixed): where a vertical line at x enters and leaves the slab between them,
// lo(x) = a_lo + b x and hi(x) = a_hi + b x. A slab whose faces stand vertical (BoxSlabs::Axis)
// bounds no z (a_lo = -inf, a_hi = +inf, b = 0) but x: |s_row + u.x x| <= h, an interval of the row.
struct RowSlab {
  double a_lo = 0.0, a_hi = 0.0, b = 0.0;
  double s_row = 0.0;  // the coordinate along the axis of (0, y, 0)
};

// What the rows share: per axis of the box, and the reciprocals every row divides by (a division
// per slab and row cost more than the texels it saved).
struct BoxSlabs {
  struct Axis {
    Eigen::Vector3d u;
    double h = 0.0;
    bool vertical = false;
    double enter = 0.0;   // the face a vertical line enters through: -h or +h along u
    double inv_uz = 0.0;  // 1 / u.z
    double b = 0.0;       // lo(x) and hi(x) slope: -u.x / u.z
    double inv_ux_dx = 0.0;  // a vertical slab: 1 / (u.x dx), 0 if u.x dx = 0
    double inv_b_dx = 0.0;   // 1 / (b dx), 0 if b = 0
  };
  std::array<Axis, 3> axis;
  bool any_vertical = false;
  std::array<std::array<double, 3>, 3> inv_db{};  // 1 / (b_k - b_m), 0 where equal or vertical
  Eigen::Vector3d centre;
  double dx, inv_dx;

  BoxSlabs(const Underside& box, double texel_dx) : centre(box.plane_from_object.translation()), dx(texel_dx), inv_dx(1.0 / texel_dx) {
    for (std::size_t k = 0; k < 3; ++k) {
      Axis& a = axis[k];
      a.u = box.plane_from_object.linear().col(Eigen::Index(k));
      a.h = box.half_extents[Eigen::Index(k)];
      a.vertical = std::fabs(a.u.z()) < kParallelSine;
      any_vertical = any_vertical || a.vertical;
      if (a.vertical) {
        a.inv_ux_dx = std::fabs(a.u.x()) >= kParallelSine ? 1.0 / (a.u.x() * dx) : 0.0;
        continue;
      }
      // Along the line the coordinate changes by u.z per metre of z: it enters the slab at the
      // face its normal turns down to.
      a.enter = a.u.z() > 0.0 ? -a.h : a.h;
      a.inv_uz = 1.0 / a.u.z();
      a.b = -a.u.x() * a.inv_uz;
      a.inv_b_dx = a.b * dx != 0.0 ? 1.0 / (a.b * dx) : 0.0;
    }
    for (std::size_t k = 0; k < 3; ++k)
      for (std::size_t m = 0; m < 3; ++m) {
        const Axis &p = axis[k], &q = axis[m];
        inv_db[k][m] = k != m && !p.vertical && !q.vertical && p.b != q.b ? 1.0 / (p.b - q.b) : 0.0;
      }
  }
  // The slabs along the row at y. The coordinate along axis u of (x, y, 0) is s_row + u.x x.
  std::array<RowSlab, 3> row(double y) const {
    std::array<RowSlab, 3> slabs;
    for (std::size_t k = 0; k < 3; ++k) {
      const Axis& a = axis[k];
      RowSlab& s = slabs[k];
      s.s_row = (y - centre.y()) * a.u.y() - centre.z() * a.u.z() - centre.x() * a.u.x();
      if (a.vertical) {
        s.a_lo = -kUnbounded, s.a_hi = kUnbounded, s.b = 0.0;
        continue;
      }
      s.a_lo = (a.enter - s.s_row) * a.inv_uz;
      s.a_hi = (-a.enter - s.s_row) * a.inv_uz;
      s.b = a.b;
    }
    return slabs;
  }
};

// The columns [first, last] of a row whose texel centres (x = x0 + gi dx) lie within every
// vertical slab, widened by one each way against rounding (texelDepth settles them); empty
// (first > last) where none does.
void clipToVerticalSlabs(const BoxSlabs& box, const std::array<RowSlab, 3>& row, double x0, long long& first,
                         long long& last) {
  for (std::size_t k = 0; k < 3; ++k) {
    const BoxSlabs::Axis& a = box.axis[k];
    if (!a.vertical) continue;
    // |s_row + ux (x0 + gi dx)| <= h, i.e. -h <= s_row + ux x0 + (ux dx) gi <= h.
    const double c0 = row[k].s_row + a.u.x() * x0;
    if (!(std::fabs(a.u.x()) >= kParallelSine)) {  // the slab's faces run along the row: all of it or none
      if (std::fabs(c0) > a.h) first = 1, last = 0;
      continue;
    }
    double g_a = (-a.h - c0) * a.inv_ux_dx, g_b = (a.h - c0) * a.inv_ux_dx;
    if (g_a > g_b) std::swap(g_a, g_b);
    // Clamped before the conversion: a slab nearly along the row puts its bounds far away.
    const double span_end = double(last) + 2.0;
    first = std::max(first, (long long)std::floor(std::clamp(g_a, -2.0, span_end)) - 1);
    last = std::min(last, (long long)std::ceil(std::clamp(g_b, -2.0, span_end)) + 1);
  }
}

// A touching texel kept for the selection: a run's end, a level stretch's end or the deepest.
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

// A row of the footprint: its slabs and the columns its vertical slabs leave.
struct FootprintRow {
  std::array<RowSlab, 3> slabs;
  long long first_col = 0, last_col = -1;
  double y = 0.0;
  int rj = 0;
};

// The box's depth at one texel centre: lowest z minus the relief's height, +inf where the box is
// absent or not within the threshold. Every depth of this path comes from here, so a texel reads
// the same whichever way it is reached (a row's loop, a level stretch's ends, the basin walk).
double texelDepth(const BoxSlabs& box, const FootprintRow& row, long long gi, double x, double height,
                  double threshold_m) {
  if (gi < row.first_col || gi > row.last_col) return kUnbounded;
  const std::array<RowSlab, 3>& s = row.slabs;
  if (box.any_vertical)
    for (std::size_t k = 0; k < 3; ++k)
      if (box.axis[k].vertical && !(std::fabs(s[k].s_row + box.axis[k].u.x() * x) <= box.axis[k].h)) return kUnbounded;
  const double lo = std::max(std::max(s[0].a_lo + s[0].b * x, s[1].a_lo + s[1].b * x), s[2].a_lo + s[2].b * x);
  const double hi = std::min(std::min(s[0].a_hi + s[0].b * x, s[1].a_hi + s[1].b * x), s[2].a_hi + s[2].b * x);
  const double d = lo - height;
  return lo <= hi && d < threshold_m ? d : kUnbounded;
}

// On a level stretch of a row (one relief height) the depth is convex in x (the largest of the
// lower faces' planes, less a constant) and the box present on an interval: the texels that
// touch are one interval, bounded by half-lines. Their ends in columns, widened by one texel each
// way against rounding (the caller settles them on texelDepth).
void touchingInterval(const BoxSlabs& box, const FootprintRow& row, double x0, double height, double threshold_m,
                      double& lo, double& hi) {
  // c0 + c1 gi <= 0 (or < 0: the same up to the widening) for gi within [lo, hi]; inv_c1 = 1 / c1.
  auto bound = [&](double c0, double c1, double inv_c1) {
    if (c1 > 0.0) hi = std::min(hi, -c0 * inv_c1);
    else if (c1 < 0.0) lo = std::max(lo, -c0 * inv_c1);
    else if (c0 > 0.0) lo = kUnbounded, hi = -kUnbounded;
  };
  for (std::size_t k = 0; k < 3; ++k) {
    const RowSlab& p = row.slabs[k];
    if (box.axis[k].vertical) continue;
    bound(p.a_lo + p.b * x0 - height - threshold_m, p.b * box.dx, box.axis[k].inv_b_dx);  // within the threshold
    for (std::size_t m = 0; m < 3; ++m) {
      const RowSlab& q = row.slabs[m];
      if (box.axis[m].vertical || m == k) continue;
      // enters before q's exit: (a_lo_p - a_hi_q) + (b_p - b_q) x <= 0
      const double inv_db = box.inv_db[k][m];
      bound(p.a_lo - q.a_hi + (p.b - q.b) * x0, (p.b - q.b) * box.dx, inv_db * box.inv_dx);
    }
  }
  lo = std::floor(lo) - 1.0, hi = std::ceil(hi) + 1.0;
}

// A row's touching texels where they are one interval on level stretches (lo > hi: none).
struct RowSpan {
  long long lo = 0, hi = -1;
  bool holds(long long gi) const { return gi >= lo && gi <= hi; }
};

// The basin walks' end, where it can be told without walking (issue 29: the three walks of a box
// at rest on a level relief were a fifth of its step, corner to corner, 40 steps each). Where
// every row's touching texels are one interval on one level relief (`spans`, all at `height`)
// and one lower face of the box is its lowest surface over all of them, the depth is that face's
// plane less the height: affine in the texel indices, d = d0 + a gi + b gj. Where a, b and a +- b
// are far from zero against rounding, the walk's comparisons are the plane's, and a texel is the
// end of a walk (no neighbour deeper) only at the end of its row that the row runs down to, and
// only if none of the four neighbours downhill of that end touches. One such texel is where
// every walk ends. Returns it as (gi, gj), or false where any condition fails (then the walks
// are walked).
bool oneBasin(const BoxSlabs& box, const std::vector<FootprintRow>& rows, const std::vector<RowSpan>& spans,
              double x0, double dy, double height, long long& basin_i, long long& basin_j) {
  const long long nj = (long long)spans.size();
  long long top = 0;
  while (top < nj && spans[std::size_t(top)].lo > spans[std::size_t(top)].hi) ++top;
  if (top == nj) return false;
  auto plane = [&](std::size_t k, const FootprintRow& row, long long gi) {
    return row.slabs[k].a_lo + row.slabs[k].b * (x0 + double(gi) * box.dx);
  };
  // The lowest face where the first touching row starts.
  int face = -1;
  for (std::size_t m = 0; m < 3; ++m)
    if (!box.axis[m].vertical &&
        (face < 0 || plane(m, rows[std::size_t(top)], spans[std::size_t(top)].lo) >
                         plane(std::size_t(face), rows[std::size_t(top)], spans[std::size_t(top)].lo)))
      face = int(m);
  if (face < 0) return false;
  const std::size_t k = std::size_t(face);
  // A face's plane is evaluated from terms no larger than `scale`; its rounding is a few times
  // 1e-16 of that. Differences are trusted beyond 1e-12 of it: ten thousand times that.
  double far_x = 0.0;
  for (const RowSpan& s : spans)
    if (s.lo <= s.hi) far_x = std::max({far_x, std::fabs(x0 + double(s.lo) * box.dx), std::fabs(x0 + double(s.hi) * box.dx)});
  const double far_y = std::max(std::fabs(rows.front().y), std::fabs(rows.back().y));
  auto scale = [&](std::size_t m) {
    const BoxSlabs::Axis& a = box.axis[m];
    return std::fabs(a.inv_uz) * (a.h + far_y + box.centre.cwiseAbs().sum()) + std::fabs(a.b) * far_x + std::fabs(height);
  };
  constexpr double kTrusted = 1e-12;
  const double rounding = kTrusted * scale(k);
  // That face lowest at both ends of every row, so over all of it (each difference is affine
  // along a row).
  for (std::size_t m = 0; m < 3; ++m) {
    if (m == k || box.axis[m].vertical) continue;
    const double margin = kTrusted * (scale(k) + scale(m));
    for (long long gj = top; gj < nj; ++gj) {
      const RowSpan& s = spans[std::size_t(gj)];
      if (s.lo > s.hi) continue;
      const FootprintRow& row = rows[std::size_t(gj)];
      if (!(plane(k, row, s.lo) - plane(m, row, s.lo) > margin) || !(plane(k, row, s.hi) - plane(m, row, s.hi) > margin))
        return false;
    }
  }
  // The depth's change per texel along the row (+gi: x grows by dx) and down the rows (+gj: y
  // falls by dy).
  const BoxSlabs::Axis& lowest = box.axis[k];
  const double a = lowest.b * box.dx, b = lowest.u.y() * lowest.inv_uz * dy;
  const double apart = 4.0 * rounding;
  if (!(std::fabs(a) > apart && std::fabs(b) > apart && std::fabs(a + b) > apart && std::fabs(a - b) > apart)) return false;
  // The four neighbours downhill: o with a oi + b oj < 0.
  std::array<std::array<long long, 2>, 4> downhill{};
  std::size_t n_down = 0;
  for (long long oj = -1; oj <= 1; ++oj)
    for (long long oi = -1; oi <= 1; ++oi)
      if (a * double(oi) + b * double(oj) < 0.0) downhill[n_down++] = {oi, oj};
  long long ends = 0;
  for (long long gj = top; gj < nj; ++gj) {
    const RowSpan& s = spans[std::size_t(gj)];
    if (s.lo > s.hi) continue;
    const long long gi = a > 0.0 ? s.lo : s.hi;
    bool end = true;
    for (std::size_t o = 0; o < n_down && end; ++o) {
      const long long j = gj + downhill[o][1];
      end = !(j >= 0 && j < nj && spans[std::size_t(j)].holds(gi + downhill[o][0]));
    }
    if (end) {
      if (++ends > 1) return false;
      basin_i = gi, basin_j = gj;
    }
  }
  return ends == 1;
}

}  // namespace

bool boxReliefContacts(const tex::TexturedSurface& surface, const Underside& box, double threshold_m,
                       ChosenReliefContacts& out, const ReliefLevelRuns* level_runs) {
  out = ChosenReliefContacts{};
  const FootprintTexels f = footprintTexels(surface, box, threshold_m);
  if (f.empty) return true;
  if (f.stride_i != 1 || f.stride_j != 1) return false;
  const long long ni = f.i1 - f.i0 + 1, nj = f.j1 - f.j0 + 1;
  out.raster.texels_visited = ni * nj;

  const tex::TextureMap& map = surface.map();
  const tex::Address address = surface.sampling().address;
  const Eigen::Vector2d texel = surface.mapping().texelSize(map);
  // The first texel centre from the surface (one place for the mapping convention), the others
  // stepped from it exactly as rasterizeRelief steps them: the same coordinates to the bit.
  const Eigen::Vector3d first = surface.texelPoint(f.i0, f.j0).q_local;
  const bool relief = surface.usesRelief();
  auto xOf = [&](long long gi) { return first.x() + double(gi) * texel.x(); };

  // Reused between steps: a resting box costs no allocation per step.
  thread_local std::vector<double> depth;          // per footprint texel: texelDepth, NaN = not read yet
  thread_local std::vector<int> columns;           // resolved column of each footprint column
  thread_local std::vector<long long> straight_to;  // last footprint column resolving to consecutive columns
  thread_local std::vector<FootprintRow> rows;
  thread_local std::vector<ReliefCandidate> kept;
  thread_local std::vector<RowSpan> spans;  // each row's touching texels while every row is one level stretch
  // The grid has a border of +inf around the footprint: the basin walk needs no bounds check.
  const long long pitch = ni + 2;
  // "Not read yet" is a NaN whose bytes are all 0xff, so the grid is cleared by memset: a
  // loop storing quiet_NaN one double at a time was a twentieth of a step at 1024².
  depth.resize(std::size_t(pitch * (nj + 2)));
  std::memset(depth.data(), 0xff, depth.size() * sizeof(double));
  for (long long gi = 0; gi < pitch; ++gi) depth[std::size_t(gi)] = depth[std::size_t((nj + 1) * pitch + gi)] = kUnbounded;
  for (long long gj = 1; gj <= nj; ++gj) depth[std::size_t(gj * pitch)] = depth[std::size_t(gj * pitch + ni + 1)] = kUnbounded;
  columns.resize(std::size_t(ni));
  straight_to.resize(std::size_t(ni));
  for (long long gi = 0; gi < ni; ++gi) columns[std::size_t(gi)] = tex::resolveIndex(f.i0 + gi, map.width(), address);
  for (long long gi = ni - 1; gi >= 0; --gi)
    straight_to[std::size_t(gi)] =
        gi + 1 < ni && columns[std::size_t(gi + 1)] == columns[std::size_t(gi)] + 1 ? straight_to[std::size_t(gi + 1)] : gi;
  rows.resize(std::size_t(nj));
  kept.clear();
  spans.assign(std::size_t(nj), RowSpan{});
  // Whether every row's touching texels are one interval, all on level stretches of one height
  // (oneBasin's premise).
  bool one_level = true;
  double level_height = std::numeric_limits<double>::quiet_NaN();

  const BoxSlabs slabs(box, texel.x());
  auto heightAt = [&](long long gi, int rj) {
    return relief ? -double(map.depth(columns[std::size_t(gi)], rj)) : 0.0;
  };
  // The depth of a footprint texel, read once.
  auto depthAt = [&](long long gi, long long gj) {
    double& d = depth[std::size_t((gj + 1) * pitch + gi + 1)];
    if (std::isnan(d)) {
      const FootprintRow& row = rows[std::size_t(gj)];
      d = texelDepth(slabs, row, gi, xOf(gi), heightAt(gi, row.rj), threshold_m);
    }
    return d;
  };

  double deepest = kUnbounded;
  long long deepest_i = -1, deepest_j = -1;
  for (long long gj = 0; gj < nj; ++gj) {
    FootprintRow& row = rows[std::size_t(gj)];
    row.y = first.y() - double(gj) * texel.y();
    row.rj = tex::resolveIndex(f.j0 + gj, map.height(), address);
    row.slabs = slabs.row(row.y);
    row.first_col = 0, row.last_col = ni - 1;
    clipToVerticalSlabs(slabs, row.slabs, first.x(), row.first_col, row.last_col);
    auto keep = [&](long long gi) {
      kept.push_back(keptTexel(f.i0 + gi, f.j0 + gj, xOf(gi), row.y, heightAt(gi, row.rj), depthAt(gi, gj)));
    };
    auto consider = [&](long long gi) {  // in scan order within the row: the first of equals stays
      const double d = depthAt(gi, gj);
      if (d < deepest) deepest = d, deepest_i = gi, deepest_j = gj;
    };
    long long run_start = -1;  // the touching run open on this row (texel by texel)
    auto closeRun = [&](long long last) {
      if (run_start < 0) return;
      keep(run_start);
      if (last != run_start) keep(last);
      run_start = -1;
    };
    // The column where a level stretch of at least kLevelStretchMin texels ends, if one starts
    // at gi (consecutive texels of one height), else gi - 1.
    auto stretchFrom = [&](long long gi) {
      if (level_runs == nullptr) return gi - 1;
      const long long same = level_runs->levelAlong(columns[std::size_t(gi)], row.rj);
      const long long to = std::min({gi + same - 1, straight_to[std::size_t(gi)], row.last_col});
      return to - gi + 1 >= kLevelStretchMin ? to : gi - 1;
    };
    double* const depth_row = depth.data() + (gj + 1) * pitch + 1;
    for (long long gi = row.first_col; gi <= row.last_col;) {
      const long long level_to = stretchFrom(gi);
      if (level_to >= gi) {
        // A level stretch: its touching interval's ends and the texels next to where its
        // faces' planes cross (the only places a convex depth can be least) are read; the
        // stretch's inside needs no reading.
        closeRun(gi - 1);
        const double height = heightAt(gi, row.rj);
        double lo = double(gi), hi = double(level_to);
        touchingInterval(slabs, row, first.x(), height, threshold_m, lo, hi);
        long long a = (long long)std::clamp(lo, double(gi), double(level_to) + 1.0);
        long long b = (long long)std::clamp(hi, double(gi) - 1.0, double(level_to));
        while (a <= b && !(depthAt(a, gj) < kUnbounded)) ++a;
        while (b >= a && !(depthAt(b, gj) < kUnbounded)) --b;
        if (a <= b) {
          std::array<long long, 8> at{};
          std::size_t n_at = 0;
          at[n_at++] = a;
          for (std::size_t k = 0; k < 3; ++k)
            for (std::size_t m = k + 1; m < 3; ++m) {
              if (slabs.inv_db[k][m] == 0.0) continue;  // parallel planes or a vertical slab: no crossing
              const RowSlab &p = row.slabs[k], &q = row.slabs[m];
              const double cross = ((q.a_lo - p.a_lo) * slabs.inv_db[k][m] - first.x()) * slabs.inv_dx;
              if (!(cross > double(a) && cross < double(b))) continue;
              at[n_at++] = (long long)std::floor(cross);
              at[n_at++] = (long long)std::floor(cross) + 1;
            }
          at[n_at++] = b;
          for (std::size_t q = 1; q < n_at; ++q)  // in scan order (a handful: insertion)
            for (std::size_t r = q; r > 0 && at[r] < at[r - 1]; --r) std::swap(at[r], at[r - 1]);
          for (std::size_t q = 0; q < n_at; ++q) consider(at[q]);
          keep(a);
          if (b != a) keep(b);
          if (one_level) {  // one interval per row (stretches meet at a wrap seam), one height
            RowSpan& span = spans[std::size_t(gj)];
            one_level = (std::isnan(level_height) || height == level_height) && (span.lo > span.hi || a == span.hi + 1);
            level_height = height;
            span = RowSpan{span.lo > span.hi ? a : span.lo, b};
          }
        }
        gi = level_to + 1;
        continue;
      }
      // Texel by texel up to where a level stretch starts: their depths in a tight loop (no
      // texel of this stretch of the row has been read), then their runs.
      long long end = gi;
      while (end < row.last_col && stretchFrom(end + 1) < end + 1) ++end;
      for (long long g = gi; g <= end; ++g) depth_row[g] = texelDepth(slabs, row, g, xOf(g), heightAt(g, row.rj), threshold_m);
      for (; gi <= end; ++gi) {
        if (depth_row[gi] < kUnbounded) {
          if (run_start < 0) run_start = gi;
          consider(gi);
          one_level = false;  // a touching texel where the relief is not level for long
        } else {
          closeRun(gi - 1);
        }
      }
    }
    closeRun(row.last_col);
  }
  if (kept.empty()) return true;
  // The deepest texel joins the kept ones in scan order, so that among equally deep texels the
  // selection takes the first in scan order, as the general rule does.
  {
    const long long j = f.j0 + deepest_j;
    const ReliefCandidate deepest_texel = keptTexel(f.i0 + deepest_i, j, xOf(deepest_i), rows[std::size_t(deepest_j)].y,
                                                    heightAt(deepest_i, rows[std::size_t(deepest_j)].rj), deepest);
    const auto at = std::lower_bound(kept.begin(), kept.end(), deepest_texel, scanOrderBefore);
    if (at == kept.end() || at->i != deepest_texel.i || at->j != deepest_texel.j) kept.insert(at, deepest_texel);
  }

  std::array<std::size_t, kMaxReliefContacts> chosen{};
  const std::size_t n = selectReliefContacts(kept, chosen);

  // snapToBasins (BasinClaim::NearestPoint), reading depths as the walk needs them: each chosen
  // texel walks to its lowest neighbour (8 around, the first of equals in scan order) while that
  // is deeper; it moves there where that bottom is nearer to it than to every other chosen texel
  // (where an earlier one went, where a later one stands).
  std::array<long long, kMaxReliefContacts> cell{};
  // Where every walk provably ends at the deepest texel, each point stays where it is.
  long long basin_i = -1, basin_j = -1;
  const bool walked = !(one_level && n > 1 && !std::isnan(level_height) &&
                        oneBasin(slabs, rows, spans, first.x(), texel.y(), level_height, basin_i, basin_j) &&
                        basin_i == kept[chosen[0]].i - f.i0 && basin_j == kept[chosen[0]].j - f.j0);
  out.one_basin = !walked;
  for (std::size_t c = 0; c < n; ++c) {
    long long gi = kept[chosen[c]].i - f.i0, gj = kept[chosen[c]].j - f.j0;
    for (; walked;) {
      long long next_i = gi, next_j = gj;
      double next_depth = depthAt(gi, gj);
      for (long long dj = -1; dj <= 1; ++dj)
        for (long long di = -1; di <= 1; ++di) {
          // The border reads +inf: never deeper.
          const long long a = gi + di, b = gj + dj;
          const double v = depthAt(a, b);
          if (v < next_depth) next_i = a, next_j = b, next_depth = v;
        }
      if (next_i == gi && next_j == gj) break;
      gi = next_i, gj = next_j;
    }
    // The plane's coordinates of the texels, as the general rule's candidates hold them.
    auto at = [&](long long i, long long j) { return Eigen::Vector2d(xOf(i), rows[std::size_t(j)].y); };
    std::array<Eigen::Vector2d, kMaxReliefContacts> others;
    std::size_t n_others = 0;
    for (std::size_t e = 0; e < n; ++e)
      if (e != c) others[n_others++] = e < c ? at(cell[e] % ni, cell[e] / ni) : at(kept[chosen[e]].i - f.i0, kept[chosen[e]].j - f.j0);
    const long long start_i = kept[chosen[c]].i - f.i0, start_j = kept[chosen[c]].j - f.j0;
    const bool claims = nearestClaims(at(start_i, start_j), at(gi, gj), std::span(others.data(), n_others));
    cell[c] = claims ? gj * ni + gi : start_j * ni + start_i;
  }

  for (std::size_t c = 0; c < n; ++c) {
    const long long gi = cell[c] % ni, gj = cell[c] / ni;
    const long long i = f.i0 + gi, j = f.j0 + gj;
    const FootprintRow& row = rows[std::size_t(gj)];
    ReliefCandidate& contact = out.contacts[c];
    contact = keptTexel(i, j, xOf(gi), row.y, heightAt(gi, row.rj), depthAt(gi, gj));
    contact.n_local = surface.texelNormal(i, j, columns[std::size_t(gi)], row.rj);
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
  snapToBasins(candidates, out.raster.stride_i, out.raster.stride_j, std::span(chosen.data(), out.count),
               BasinClaim::NearestPoint);
  for (std::size_t c = 0; c < out.count; ++c) out.contacts[c] = candidates[chosen[c]];
  return out;
}

}  // namespace thx::phys
