#include "clients/physics/ball_on_flat_ground.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include "clients/physics/mesh_relief_chart.hpp"
#include "textures/sampling.hpp"

namespace thx::phys {

namespace {

// A relief's flatness is read over at most this many texels (a larger disc: not flat ground here).
constexpr long long kMostFlatnessTexels = 1 << 16;
// A block's points are measured from the relief's top under them where they span no more than
// this many of its texels (more: from its top under the whole disc).
constexpr long long kMostBlockTexels = 1 << 10;
// The refinement's first step and its last, in texels of the ball's texture.
constexpr double kRefineFirstStep = 0.5, kRefineLastStep = 1.0 / BallTexelGrid::kOffsetSteps;
// Two refined points nearer than this (in texels, along the ball's surface) are one basin's,
// reached from two texels (either side of a cube face's edge): the second is dropped.
constexpr double kSameBasinTexels = 0.25;
// A texel across a face's edge as low as an edge texel within this (m) is a tie: where the lowest
// point lies on the edge itself, each face's edge texel has the other's mirror image across it,
// computed another way and a rounding lower, and neither would be a basin.
constexpr double kAcrossEdgeTie = 1e-12;

// The touching disc's radius: where the sphere, its lowest point `lowest_gap` above the ground,
// lies within `threshold` of it.
double touchingRadius(double r, double lowest_gap, double threshold) {
  const double h = std::min(threshold - lowest_gap, r);
  return h > 0.0 ? std::sqrt(std::max(0.0, 2.0 * r * h - h * h)) : 0.0;
}

struct Texel {
  int face = 0, k = 0, l = 0;
  double depth = 0.0;
};

// The texels (unresolved indices) holding the plane's box [lo, hi] and one round them, which a
// bilinear reading anywhere in the box may touch. A plane mapping takes i from x alone and j from
// y alone, so two corners bound them.
struct TexelSpan {
  long long i0 = 0, i1 = 0, j0 = 0, j1 = 0;
  long long count() const { return (i1 - i0 + 1) * (j1 - j0 + 1); }
};
TexelSpan texelsRound(const tex::TexturedSurface& surface, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  long long ia = 0, ja = 0, ib = 0, jb = 0;
  surface.texelContaining(lo.x(), lo.y(), ia, ja);
  surface.texelContaining(hi.x(), hi.y(), ib, jb);
  return {std::min(ia, ib) - 1, std::max(ia, ib) + 1, std::min(ja, jb) - 1, std::max(ja, jb) + 1};
}

// The relief's depth codes over the texels under the ball's touching disc (the part of its sphere
// within `threshold_m` of the ground) and one texel round them: the least (the highest ground) and
// the most, with a texel holding the least (resolved); nullopt where there is no disc, it holds too
// many texels, or the depth bends by more than `most_bend` codes from one texel to the next along
// a row or a column (its second difference there; the read stops at once on a textured relief).
struct CodeRange {
  std::uint16_t lo = 0, hi = 0;
  int ri = 0, rj = 0;
};
std::optional<CodeRange> depthCodesUnder(const tex::TexturedSurface& surface, const Underside& ball, double threshold_m,
                                         const GroundBend* bend, double most_bend) {
  const Eigen::Vector3d c = ball.plane_from_object.translation();
  const tex::TextureMap& map = surface.map();
  // A relief lies at or under its plane (height <= 0), and the bend raises it no higher than it
  // rises under the ball: the disc within the threshold and that rise of the plane holds the disc
  // within the threshold of the relief, wherever that lies.
  const double rise =
      bend ? bend->highestOver(Eigen::AlignedBox2d(c.head<2>() - Eigen::Vector2d::Constant(ball.radius),
                                                   c.head<2>() + Eigen::Vector2d::Constant(ball.radius)))
           : 0.0;
  const double rho = touchingRadius(ball.radius, c.z() - ball.radius, threshold_m + rise);
  if (!(rho > 0.0)) return std::nullopt;
  const TexelSpan span = texelsRound(surface, c.head<2>() - Eigen::Vector2d::Constant(rho),
                                     c.head<2>() + Eigen::Vector2d::Constant(rho));
  if (span.count() > kMostFlatnessTexels) return std::nullopt;
  const long long i0 = span.i0, i1 = span.i1, j0 = span.j0, j1 = span.j1;
  const tex::Address address = surface.sampling().address;
  const std::size_t width = std::size_t(i1 - i0 + 1);
  // The last three rows read, to take second differences down the columns.
  thread_local std::vector<int> rows;
  rows.resize(3 * width);
  const int most = int(std::min(most_bend, 65535.0));
  auto bends = [most](int before, int at, int after) { return std::abs(before - 2 * at + after) > most; };
  CodeRange range;
  range.lo = 65535, range.hi = 0;
  for (long long j = j0; j <= j1; ++j) {
    const int rj = tex::resolveIndex(j, map.height(), address);
    int* row = rows.data() + std::size_t(j - j0) % 3 * width;
    for (std::size_t x = 0; x < width; ++x) {
      const int ri = tex::resolveIndex(i0 + (long long)x, map.width(), address);
      const std::uint16_t code = map.depthCode(ri, rj);
      row[x] = code;
      if (code < range.lo) range.lo = code, range.ri = ri, range.rj = rj;
      range.hi = std::max(range.hi, code);
      if (x >= 2 && bends(row[x - 2], row[x - 1], row[x])) return std::nullopt;
    }
    if (j - j0 >= 2) {
      const int* above = rows.data() + std::size_t(j - j0 - 1) % 3 * width;
      const int* above2 = rows.data() + std::size_t(j - j0 - 2) % 3 * width;
      for (std::size_t x = 0; x < width; ++x)
        if (bends(above2[x], above[x], row[x])) return std::nullopt;
    }
  }
  return range;
}

}  // namespace

std::optional<FlatGround> flatGround(const tex::TexturedSurface& surface, const Underside& ball, double threshold_m,
                                     const GroundBend* bend) {
  if (isSmoothChart(surface)) return FlatGround{};  // it stores no depth
  if (!surface.usesRelief()) return std::nullopt;
  const double step = surface.map().depthStep();
  const double most_bend = step > 0.0 ? std::floor(kSmoothReliefBend / step) : 0.0;
  const std::optional<CodeRange> range = depthCodesUnder(surface, ball, threshold_m, bend, most_bend);
  if (!range) return std::nullopt;
  const double top = -double(surface.map().depth(range->ri, range->rj));
  return FlatGround{top, range->lo != range->hi};
}

std::optional<double> flatGroundHeight(const tex::TexturedSurface& surface, const Underside& ball, double threshold_m,
                                       const GroundBend* bend) {
  const std::optional<FlatGround> ground = flatGround(surface, ball, threshold_m, bend);
  if (!ground || ground->read_relief) return std::nullopt;
  return ground->height_m;
}

bool reliefSmooth(const tex::TexturedSurface& surface, const Underside& ball, double threshold_m,
                  const GroundBend* bend) {
  const std::optional<FlatGround> ground = flatGround(surface, ball, threshold_m, bend);
  return ground && ground->read_relief;
}

std::size_t ballOnFlatGround(const BallTexelGrid& grid, const tex::TexturedSurface& surface,
                             const Underside& ball, double ground_z, const GroundBend* bend, double threshold_m,
                             double closing_within_m, BallBasinHint& hint,
                             std::array<ReliefCandidate, kMaxBallBasins>& out, bool read_relief) {
  const double r = ball.radius;
  const Eigen::Matrix3d rot = ball.plane_from_object.linear();
  const Eigen::Vector3d c = ball.plane_from_object.translation();
  const Eigen::Vector3d down = -rot.row(2).transpose();  // the plane's -z in the object frame
  // A smooth relief is read under each point (its bilinear height, as the contacts read it), on
  // the bent ground's path, which measures every point's gap to the ground under it; `ground_z`
  // is then its top under the ball, which bounds it there.
  static const GroundBend kUnbent{};
  if (read_relief && !bend) bend = &kUnbent;
  auto groundUnder = [&](double x, double y) {
    const double bent = bend ? bend->height(x, y) : 0.0;
    if (!read_relief) return ground_z + bent;
    return bent - double(tex::sampleDepth(surface.map(), surface.mapping().uvOfLocal({x, y}), surface.sampling()));
  };
  // A texel's gap to the ground: its point p = c + R w (r - recess), measured along z to the
  // ground under p (on flat ground the same for every p, so only p's height counts).
  auto gapOf = [&](const Eigen::Vector3d& w, double recess) {
    if (!bend) return c.z() - down.dot(w) * (r - recess) - ground_z;
    const Eigen::Vector3d p = c + rot * (w * (r - recess));
    return p.z() - groundUnder(p.x(), p.y());
  };
  // Where the ground is bent: its upward normal under the centre, n = (-slope, 1) / L, and the
  // most it curves upward (the larger eigenvalue of its curvatures, no less than 0).
  Eigen::Vector3d n_under = Eigen::Vector3d::UnitZ();
  double slope_length = 1.0, curving_up = 0.0, centre_gap = c.z() - ground_z;
  if (bend) {
    const Eigen::Vector2d s = bend->slope(c.x(), c.y());
    n_under = Eigen::Vector3d(-s.x(), -s.y(), 1.0);
    slope_length = n_under.norm();
    n_under /= slope_length;
    const double mean = 0.5 * (bend->xx + bend->yy), half = 0.5 * (bend->xx - bend->yy);
    curving_up = std::max(0.0, mean + std::sqrt(half * half + bend->xy * bend->xy));
    // The level and the bend alone: a relief read under each point lies no higher than its top
    // under the ball, so the bound below holds for it too.
    centre_gap = c.z() - ground_z - bend->height(c.x(), c.y());
  }
  // The smooth sphere's gap straight down the ground's normal: on flat ground its lowest point's.
  const double lowest_gap = bend ? [&] {
    const Eigen::Vector3d p = c - r * n_under;
    return p.z() - groundUnder(p.x(), p.y());
  }()
                                 : c.z() - r - ground_z;
  const Eigen::Vector3d n_object = rot.transpose() * n_under;  // that normal in the object frame

  // Per face, the gaps of the texels read (the rest +inf: open, as a deeper one); every entry is
  // +inf again when the call returns, whichever ball's grid the next call reads.
  thread_local std::array<std::vector<double>, 6> gaps;
  thread_local std::vector<Texel> read, basins;
  const std::size_t face_texels = std::size_t(grid.columns()) * std::size_t(grid.rows());
  for (std::vector<double>& g : gaps)
    if (g.size() < face_texels) g.assign(face_texels, std::numeric_limits<double>::infinity());
  auto forgetRead = [&] {
    for (const Texel& t : read) gaps[std::size_t(t.face)][grid.at(t.k, t.l)] = std::numeric_limits<double>::infinity();
    read.clear();
  };
  std::size_t found = 0;

  // Reads every texel whose smooth sphere lies within `bound` of flat ground (a cap round the
  // plane's -z).
  auto readFlatWithin = [&](double bound) {
    // lowest_gap + r (1 - cos(angle from down)) <= bound.
    const double cos_cap = 1.0 - (bound - lowest_gap) / r;
    if (cos_cap > 1.0) return;
    const double cap = std::acos(std::max(-1.0, cos_cap)), sin_cap = std::sin(cap);
    for (int f = 0; f < 6; ++f) {
      std::vector<double>& g = gaps[std::size_t(f)];
      // down . w = (down_a sign + down_b tanU + down_d tanV) / |(1, tanU, tanV)|.
      const int a = f / 2;
      const double down_a = f % 2 ? -down[a] : down[a], down_b = down[(a + 1) % 3], down_d = down[(a + 2) % 3];
      for (const BallTexelGrid::Block& b : grid.blocks(f)) {
        // Every texel of the block lies more than the cap round from down: skip it.
        const double cos_reach = cos_cap * b.cos_spread - sin_cap * b.sin_spread;  // cos(cap + spread)
        if (cap + b.spread < std::numbers::pi && b.centre.dot(down) < cos_reach) continue;
        for (int l = b.l0; l < b.l1; ++l) {
          const double tv = grid.tanV(l), row = down_a + down_d * tv, row_length2 = 1.0 + tv * tv;
          for (int k = b.k0; k < b.k1; ++k) {
            const double tu = grid.tanU(k);
            const double cos_down = (row + down_b * tu) / std::sqrt(row_length2 + tu * tu);
            if (cos_down < cos_cap) continue;
            const std::size_t at = grid.at(k, l);
            const double gap = c.z() - cos_down * (r - grid.recess(at)) - ground_z;
            g[at] = gap;
            read.push_back({f, k, l, gap});
          }
        }
      }
    }
  };
  // The highest a relief read under each point lies under a block's points (ground_z where they
  // span too many of its texels): the relief's top over the texels round the box that holds them.
  // A point is c + s (rot w) with s within r - deepestRecess and r and w within the block's
  // spread (as a chord) of its middle direction.
  const tex::TextureMap& map = surface.map();
  const tex::Address address = surface.sampling().address;
  auto reliefTopUnder = [&](const BallTexelGrid::Block& b) {
    const Eigen::Vector3d middle = rot * b.centre;
    const double near = r - grid.deepestRecess();
    Eigen::Vector2d lo, hi;
    for (int a = 0; a < 2; ++a) {
      const double least = middle[a] - b.spread, most = middle[a] + b.spread;
      lo[a] = c[a] + std::min(near * least, r * least), hi[a] = c[a] + std::max(near * most, r * most);
    }
    const TexelSpan span = texelsRound(surface, lo, hi);
    if (span.count() > kMostBlockTexels) return ground_z;
    std::uint16_t least = 65535;
    int li = 0, lj = 0;
    for (long long j = span.j0; j <= span.j1; ++j) {
      const int rj = tex::resolveIndex(j, map.height(), address);
      for (long long i = span.i0; i <= span.i1; ++i) {
        const int ri = tex::resolveIndex(i, map.width(), address);
        if (const std::uint16_t code = map.depthCode(ri, rj); code < least) least = code, li = ri, lj = rj;
      }
    }
    return -double(map.depth(li, lj));
  };
  // Reads every texel whose point lies within `bound` of bent ground. A block is skipped where
  // even the smooth sphere lies farther above the ground over all of it: the ground's height
  // h(c + r w) is quadratic, so the smooth sphere's gap at direction w (plane frame) is the
  // centre's gap + r L (w . n) - r^2 (w_xy^T H w_xy) / 2, no less than the centre's gap +
  // r L min(w . n, 0) - r^2 curving_up |w_xy|^2 / 2; a recessed point's gap (r - recess for r) is
  // no less than that bound either, as curving_up >= 0.
  auto readBentWithin = [&](double bound) {
    const double centre_bent = bend->height(c.x(), c.y());
    for (int f = 0; f < 6; ++f) {
      std::vector<double>& g = gaps[std::size_t(f)];
      const int a = f / 2;
      // The face's axes in the plane frame: a texel's point is c + (r - recess) (A + tanU B + tanV D) / len.
      const Eigen::Vector3d A = (f % 2 ? -1.0 : 1.0) * rot.col(a), B = rot.col((a + 1) % 3), D = rot.col((a + 2) % 3);
      for (const BallTexelGrid::Block& b : grid.blocks(f)) {
        const double cos_n = b.centre.dot(n_object), sin_n = std::sqrt(std::max(0.0, 1.0 - cos_n * cos_n));
        // The least w . n over the block: cos(angle + spread), -1 past pi.
        const double least_dot = cos_n <= -b.cos_spread ? -1.0 : cos_n * b.cos_spread - sin_n * b.sin_spread;
        // The most |w_xy|^2 over the block: sin^2 of its angle from -z plus the spread (1 past pi / 2).
        const double cos_z = b.centre.dot(down), sin_z = std::sqrt(std::max(0.0, 1.0 - cos_z * cos_z));
        const double most_sin = cos_z <= b.sin_spread ? 1.0 : sin_z * b.cos_spread + cos_z * b.sin_spread;
        const double least_rise = r * slope_length * std::min(least_dot, 0.0) - 0.5 * r * r * curving_up * most_sin * most_sin;
        if (centre_gap + least_rise > bound) continue;
        // A relief read under each point lies no higher than its top under the block's points
        // (reliefTopUnder): on a dish or a slope its top under the whole disc lies tens of
        // micrometres above the ground under the ball, so the block, and then each point, is
        // measured from the block's top before the relief is read under it.
        const double top = read_relief ? reliefTopUnder(b) : ground_z;
        if (read_relief && c.z() - top - centre_bent + least_rise > bound) continue;
        for (int l = b.l0; l < b.l1; ++l) {
          const double tv = grid.tanV(l), row_length2 = 1.0 + tv * tv;
          const Eigen::Vector3d row = A + tv * D;
          for (int k = b.k0; k < b.k1; ++k) {
            const double tu = grid.tanU(k);
            const std::size_t at = grid.at(k, l);
            const Eigen::Vector3d p = c + ((r - grid.recess(at)) / std::sqrt(row_length2 + tu * tu)) * (row + tu * B);
            const double bent = bend->height(p.x(), p.y());
            if (read_relief && p.z() - top - bent > bound) continue;
            const double gap = read_relief ? p.z() - groundUnder(p.x(), p.y()) : p.z() - (ground_z + bent);
            if (gap > bound) continue;
            g[at] = gap;
            read.push_back({f, k, l, gap});
          }
        }
      }
    }
  };
  // The texels read that are no deeper than any of their eight neighbours, deepest first.
  auto findBasins = [&] {
    for (const Texel& t : read) {
      const std::vector<double>& g = gaps[std::size_t(t.face)];
      bool basin = true, by_edge = false;
      for (int dl = -1; dl <= 1 && basin; ++dl)
        for (int dk = -1; dk <= 1 && basin; ++dk) {
          const int k = t.k + dk, l = t.l + dl;
          if (dk == 0 && dl == 0) continue;
          if (k < 0 || l < 0 || k >= grid.columns() || l >= grid.rows()) {
            by_edge = true;
            continue;
          }
          basin = g[grid.at(k, l)] >= t.depth;
        }
      // By the face's edge, the next face's texels nearest where its grid's would lie stand for
      // the neighbours the grid lacks: an edge texel is otherwise the lowest of its face wherever
      // the ball's lowest point lies on the next face within the disc, and a rolling ball's
      // contact there, ahead of its lowest point, braked it (0.3 % slow in 0.3 s).
      for (int dl = -1; dl <= 1 && basin && by_edge; ++dl)
        for (int dk = -1; dk <= 1 && basin; ++dk) {
          const int k = t.k + dk, l = t.l + dl;
          if (!(k < 0 || l < 0 || k >= grid.columns() || l >= grid.rows())) continue;
          int face = 0, kn = 0, ln = 0;
          grid.texelNearest(grid.directionAt(t.face, k, l), face, kn, ln);
          if (face == t.face) continue;  // past a corner, back on this face: its own texels decide
          basin = gapOf(grid.direction(face, kn, ln), grid.recess(kn, ln)) >= t.depth - kAcrossEdgeTie;
        }
      if (basin) basins.push_back(t);
    }
    // The deepest first; ties in the order read (the faces', then the texels' order), so a step
    // is the same for the same pose.
    std::stable_sort(basins.begin(), basins.end(), [](const Texel& a, const Texel& b) { return a.depth < b.depth; });
    found = basins.size();
  };
  auto readWithin = [&](double bound) {
    forgetRead();
    basins.clear();
    if (bend) readBentWithin(bound);
    else readFlatWithin(bound);
    findBasins();
  };
  auto fourthGap = [&] { return basins[kMaxReliefContacts - 1].depth; };

  bool exact = false;
  if (std::isfinite(hint.reach_m)) {
    const double bound = firstReadBound(hint, lowest_gap, threshold_m, closing_within_m);
    if (bound < threshold_m) {
      readWithin(bound);
      exact = found >= kMaxReliefContacts && fourthGap() < bound;
    }
  }
  if (!exact) readWithin(threshold_m);
  hint.reach_m = found >= kMaxReliefContacts ? fourthGap() - lowest_gap : std::numeric_limits<double>::quiet_NaN();
  forgetRead();

  // Each basin kept refined to its bottom between the texels, in the ball's texture coordinates.
  const double same_basin = kSameBasinTexels * std::min(grid.texelU(), grid.texelV()) / r;  // as a chord of the unit sphere
  std::array<Eigen::Vector3d, kMaxBallBasins> kept_w;
  std::size_t kept = 0;
  for (std::size_t b = 0; b < found && kept < kMaxBallBasins; ++b) {
    const Texel& t = basins[b];
    if (kept >= kMaxReliefContacts && !(t.depth < closing_within_m)) break;
    double best = t.depth, du = 0.0, dv = 0.0;
    Eigen::Vector3d best_w = grid.direction(t.face, t.k, t.l);
    double best_recess = grid.recess(t.k, t.l);
    for (double h = kRefineFirstStep; h >= kRefineLastStep; h *= 0.5) {
      for (bool moved = true; moved;) {
        moved = false;
        for (int su = -1; su <= 1; ++su)
          for (int sv = -1; sv <= 1; ++sv) {
            const double nu = du + su * h, nv = dv + sv * h;
            if ((su == 0 && sv == 0) || std::fabs(nu) > 1.0 || std::fabs(nv) > 1.0) continue;
            Eigen::Vector3d w;
            double recess = 0.0;
            grid.pointAtOffset(t.face, t.k, t.l, nu, nv, w, recess);
            const double gap = gapOf(w, recess);
            if (gap < best) best = gap, du = nu, dv = nv, best_w = w, best_recess = recess, moved = true;
          }
      }
    }
    bool same = false;
    for (std::size_t q = 0; q < kept && !same; ++q) same = (kept_w[q] - best_w).norm() < same_basin;
    if (same) continue;
    kept_w[kept] = best_w;
    const Eigen::Vector3d p = c + rot * (best_w * (r - best_recess));
    ReliefCandidate& o = out[kept++];
    const tex::SurfacePoint s = surface.at(p.x(), p.y());
    o.p_surface = Eigen::Vector3d(p.x(), p.y(), groundUnder(p.x(), p.y()));
    o.n_local = bend ? bend->tilt(s.n_local, p.x(), p.y()) : s.n_local;
    o.depth = best;
    surface.texelContaining(p.x(), p.y(), o.i, o.j);
  }
  // Deepest first (refining can change the order), as the contacts are added.
  std::stable_sort(out.begin(), out.begin() + std::ptrdiff_t(kept),
                   [](const ReliefCandidate& a, const ReliefCandidate& b) { return a.depth < b.depth; });
  return kept;
}

}  // namespace thx::phys
