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

// A chosen texel as the general rule's candidates hold it.
ReliefCandidate keptTexel(long long i, long long j, double x, double y, double height, double depth) {
  ReliefCandidate c;
  c.p_surface = Eigen::Vector3d(x, y, height);
  c.depth = depth;
  c.i = i;
  c.j = j;
  return c;
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

// A stretch of a row whose texels the selection reads: read texel by texel (every touching texel
// may win), or one level stretch's touching interval [from, to] at `height`, whose depth is convex.
struct RowPiece {
  long long gj = 0, from = 0, to = -1;
  bool level = false;
  double height = 0.0;
  double least = 0.0;  // a level stretch's least depth
};

// Where along a row (in columns) the line through the box's centre along `axis` crosses it:
// the quarters change there. NaN where the row runs along the line.
double quarterCrossing(const Eigen::Vector2d& centre, const Eigen::Vector2d& axis, double y, double x0, double inv_dx) {
  if (axis.x() == 0.0) return std::numeric_limits<double>::quiet_NaN();
  // (x - cx) a.x + (y - cy) a.y = 0
  return (centre.x() - (y - centre.y()) * axis.y() / axis.x() - x0) * inv_dx;
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
  thread_local std::vector<RowPiece> pieces;  // what the selection reads, in scan order
  // The grid has a border of +inf around the footprint.
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
  pieces.clear();

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
  // Where a level stretch's faces' planes cross along its row (in columns, within (a, b)): its
  // depth is affine between them. At most three.
  auto faceCrossings = [&](const FootprintRow& row, long long a, long long b, std::array<double, 3>& at) {
    std::size_t n = 0;
    for (std::size_t k = 0; k < 3; ++k)
      for (std::size_t m = k + 1; m < 3; ++m) {
        if (slabs.inv_db[k][m] == 0.0) continue;  // parallel planes or a vertical slab: no crossing
        const RowSlab &p = row.slabs[k], &q = row.slabs[m];
        const double cross = ((q.a_lo - p.a_lo) * slabs.inv_db[k][m] - first.x()) * slabs.inv_dx;
        if (cross > double(a) && cross < double(b)) at[n++] = cross;
      }
    return n;
  };

  // Pass 1: every row's depths as far as the deepest texel needs them, and the pieces the
  // selection reads.
  double deepest = kUnbounded;
  long long deepest_i = -1, deepest_j = -1;
  for (long long gj = 0; gj < nj; ++gj) {
    FootprintRow& row = rows[std::size_t(gj)];
    row.y = first.y() - double(gj) * texel.y();
    row.rj = tex::resolveIndex(f.j0 + gj, map.height(), address);
    row.slabs = slabs.row(row.y);
    row.first_col = 0, row.last_col = ni - 1;
    clipToVerticalSlabs(slabs, row.slabs, first.x(), row.first_col, row.last_col);
    auto consider = [&](long long gi) {  // of equal depths the first in scan order
      const double d = depthAt(gi, gj);
      if (d < deepest || (d == deepest && gj == deepest_j && gi < deepest_i)) deepest = d, deepest_i = gi, deepest_j = gj;
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
        // A level stretch: the ends of its touching interval and the texels by where its faces'
        // planes cross (the only places a convex depth can be least) are read; the inside needs
        // no reading.
        const double height = heightAt(gi, row.rj);
        double lo = double(gi), hi = double(level_to);
        touchingInterval(slabs, row, first.x(), height, threshold_m, lo, hi);
        long long a = (long long)std::clamp(lo, double(gi), double(level_to) + 1.0);
        long long b = (long long)std::clamp(hi, double(gi) - 1.0, double(level_to));
        while (a <= b && !(depthAt(a, gj) < kUnbounded)) ++a;
        while (b >= a && !(depthAt(b, gj) < kUnbounded)) --b;
        if (a <= b) {
          std::array<double, 3> cross{};
          const std::size_t n_cross = faceCrossings(row, a, b, cross);
          double least = kUnbounded;
          auto read = [&](long long g) { consider(g), least = std::min(least, depthAt(g, gj)); };
          read(a);
          for (std::size_t c = 0; c < n_cross; ++c) read((long long)std::floor(cross[c])), read((long long)std::floor(cross[c]) + 1);
          read(b);
          pieces.push_back(RowPiece{gj, a, b, true, height, least});
        }
        gi = level_to + 1;
        continue;
      }
      // Texel by texel up to where a level stretch starts: their depths in a tight loop (no
      // texel of this stretch of the row has been read).
      long long end = gi;
      while (end < row.last_col && stretchFrom(end + 1) < end + 1) ++end;
      for (long long g = gi; g <= end; ++g) depth_row[g] = texelDepth(slabs, row, g, xOf(g), heightAt(g, row.rj), threshold_m);
      bool touching = false;
      for (long long g = gi; g <= end; ++g)
        if (depth_row[g] < kUnbounded) consider(g), touching = true;
      if (touching) pieces.push_back(RowPiece{gj, gi, end, false, 0.0, 0.0});
      gi = end + 1;
    }
  }
  if (deepest_i < 0) return true;

  // Pass 2: the quarter rule (contact_selection.hpp, BoxQuarters) offered every texel that can
  // win. Along a level stretch the score (depth less the spread preference, concave
  // where one face is lowest) is least at the ends of where one face is lowest, of each quarter's
  // part and of the part within the tolerance of the deepest: those ends are offered, with a
  // texel either side of each crossing against rounding.
  BoxQuarters quarters = quartersUnder(box, map.depthStep());
  quarters.setDeepest(deepest, Eigen::Vector2d(xOf(deepest_i), rows[std::size_t(deepest_j)].y));
  const double within = deepest + quarters.depthTolerance();
  const Eigen::Vector2d centre = quarters.centre();
  auto offer = [&](long long gi, long long gj) {
    const double d = depthAt(gi, gj);
    if (d < kUnbounded) quarters.offer(std::size_t(gj * ni + gi), Eigen::Vector2d(xOf(gi), rows[std::size_t(gj)].y), d);
  };
  // The pieces from both ends of the footprint inwards: a level box's corners come first, and
  // then every piece between is refused whole (the offers name their texels' places in scan
  // order, so their order does not change the answer).
  for (std::size_t visited = 0; visited < pieces.size(); ++visited) {
    const RowPiece& piece = pieces[visited % 2 == 0 ? visited / 2 : pieces.size() - 1 - visited / 2];
    const FootprintRow& row = rows[std::size_t(piece.gj)];
    if (!piece.level) {
      for (long long g = piece.from; g <= piece.to; ++g) offer(g, piece.gj);
      continue;
    }
    const long long a = piece.from, b = piece.to;
    // No texel of a level stretch scores below its least depth less the preference at its
    // farthest end (the distance is convex along the row): refused whole where every quarter has
    // a lower score already.
    {
      const double far = std::max(Eigen::Vector2d(xOf(a) - centre.x(), row.y - centre.y()).norm(),
                                  Eigen::Vector2d(xOf(b) - centre.x(), row.y - centre.y()).norm());
      if (quarters.refuses(piece.least, far)) continue;
    }
    auto around = [&](double cross) {  // the texels either side of a crossing, one more where it is near a texel
      if (!(cross > double(a) - 2.0 && cross < double(b) + 2.0)) return;
      const long long g = (long long)std::floor(cross);
      const double frac = cross - double(g);
      for (long long t = std::max(g - (frac < 1e-6 ? 1 : 0), a); t <= std::min(g + (frac > 1.0 - 1e-6 ? 2 : 1), b); ++t)
        offer(t, piece.gj);
    };
    offer(a, piece.gj);
    offer(b, piece.gj);
    std::array<double, 3> cross{};
    const std::size_t n_cross = faceCrossings(row, a, b, cross);
    for (std::size_t c = 0; c < n_cross; ++c) around(cross[c]);
    for (const Eigen::Vector2d& axis : quarters.axes()) around(quarterCrossing(centre, axis, row.y, first.x(), slabs.inv_dx));
    // Where the depth is within the tolerance of the deepest: one interval (the depth is convex),
    // none where its least is not, all of it where both ends are.
    if (piece.least <= within && !(depthAt(a, piece.gj) <= within && depthAt(b, piece.gj) <= within)) {
      double lo = double(a), hi = double(b);
      touchingInterval(slabs, row, first.x(), piece.height, within, lo, hi);
      long long r0 = (long long)std::clamp(lo, double(a), double(b) + 1.0);
      long long r1 = (long long)std::clamp(hi, double(a) - 1.0, double(b));
      while (r0 <= r1 && !(depthAt(r0, piece.gj) <= within)) ++r0;
      while (r1 >= r0 && !(depthAt(r1, piece.gj) <= within)) --r1;
      if (r0 <= r1) offer(r0, piece.gj), offer(r1, piece.gj);
    }
  }

  std::array<std::size_t, kMaxReliefContacts> cells{};
  const std::size_t n = quarters.chosen(cells);
  for (std::size_t c = 0; c < n; ++c) {
    const long long gi = (long long)cells[c] % ni, gj = (long long)cells[c] / ni;
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
  BoxQuarters quarters = quartersUnder(box, surface.map().depthStep());
  out.count = selectBoxQuarterContacts(candidates, quarters, chosen);
  for (std::size_t c = 0; c < out.count; ++c) out.contacts[c] = candidates[chosen[c]];
  return out;
}

BoxQuarters quartersUnder(const Underside& box, double depth_tolerance) {
  const Eigen::Matrix3d& axes = box.plane_from_object.linear();
  const int down = mostUprightAxis(axes);
  return BoxQuarters(box.plane_from_object.translation().head<2>(), axes.col((down + 1) % 3).head<2>(),
                     axes.col((down + 2) % 3).head<2>(), kPreferSpread, depth_tolerance, box.half_extents.norm());
}

}  // namespace thx::phys
