#include "textures/ball_on_relief.hpp"

#include <algorithm>
#include <cmath>

namespace thx::tex {

namespace {

long long floorDiv(long long a, int shift) { return a >= 0 ? a >> shift : -((-a + (1LL << shift) - 1) >> shift); }

}  // namespace

BallOnRelief::BallOnRelief(const TextureMap& map, Address address) : max_depth_m_(map.maxDepth()), address_(address) {
  Level front, behind;
  front.width = behind.width = map.width();
  front.height = behind.height = map.height();
  front.max_height.resize(std::size_t(map.width()) * std::size_t(map.height()));
  behind.max_height.resize(front.max_height.size());
  for (int j = 0; j < map.height(); ++j)
    for (int i = 0; i < map.width(); ++i) {
      const std::size_t k = std::size_t(j) * std::size_t(map.width()) + std::size_t(i);
      front.max_height[k] = -map.depth(i, j);
      behind.max_height[k] = map.depth(i, j);
    }
  front_ = pyramidOf(std::move(front));
  behind_ = pyramidOf(std::move(behind));
}

std::vector<BallOnRelief::Level> BallOnRelief::pyramidOf(Level base) {
  std::vector<Level> levels;
  levels.push_back(std::move(base));
  // Only while both sides halve exactly, so that a block of a level is the same texels wherever
  // the wrapped texture repeats (a side that does not divide leaves the finer levels to search).
  while (levels.back().width % 2 == 0 && levels.back().height % 2 == 0) {
    const Level& fine = levels.back();
    Level coarse;
    coarse.width = fine.width / 2;
    coarse.height = fine.height / 2;
    coarse.max_height.resize(std::size_t(coarse.width) * std::size_t(coarse.height));
    for (int j = 0; j < coarse.height; ++j)
      for (int i = 0; i < coarse.width; ++i)
        coarse.max_height[std::size_t(j) * std::size_t(coarse.width) + std::size_t(i)] =
            std::max(std::max(fine.at(2 * i, 2 * j), fine.at(2 * i + 1, 2 * j)),
                     std::max(fine.at(2 * i, 2 * j + 1), fine.at(2 * i + 1, 2 * j + 1)));
    levels.push_back(std::move(coarse));
  }
  return levels;
}

double BallOnRelief::bilinear(const Level& l, double s, double t, Eigen::Vector2d* gradient) const {
  const double s0 = std::floor(s), t0 = std::floor(t), fs = s - s0, ft = t - t0;
  const long long i0 = (long long)s0, j0 = (long long)t0;
  const int ia = resolveIndex(i0, l.width, address_), ib = resolveIndex(i0 + 1, l.width, address_);
  const int ja = resolveIndex(j0, l.height, address_), jb = resolveIndex(j0 + 1, l.height, address_);
  const double a = l.at(ia, ja), b = l.at(ib, ja), c = l.at(ia, jb), d = l.at(ib, jb);
  if (gradient) *gradient = {(1.0 - ft) * (b - a) + ft * (d - c), (1.0 - fs) * (c - a) + fs * (d - b)};
  return (1.0 - ft) * ((1.0 - fs) * a + fs * b) + ft * ((1.0 - fs) * c + fs * d);
}

BallOnRelief::Touch BallOnRelief::touch(TexCoord uv, const Eigen::Vector2d& metres_per_uv, double radius_m,
                                        bool from_behind, std::optional<Texel> near) const {
  return *search(uv, metres_per_uv, radius_m, from_behind, Half{}, near);
}

std::optional<BallOnRelief::Touch> BallOnRelief::touchOnHalf(TexCoord uv, const Eigen::Vector2d& metres_per_uv,
                                                             double radius_m, bool from_behind, Half half,
                                                             std::optional<Texel> near) const {
  return search(uv, metres_per_uv, radius_m, from_behind, half, near);
}

std::optional<BallOnRelief::Touch> BallOnRelief::search(TexCoord uv, const Eigen::Vector2d& metres_per_uv,
                                                        double radius_m, bool from_behind, Half half,
                                                        std::optional<Texel> near) const {
  Touch out;
  const std::vector<Level>& levels = from_behind ? behind_ : front_;
  const int width = levels.front().width, height = levels.front().height;
  const double r = radius_m, r2 = r * r;
  const double du = metres_per_uv.x() / width, dv = metres_per_uv.y() / height;  // metres per texel
  if (!(r > 0.0) || !(du > 0.0) || !(dv > 0.0) || !std::isfinite(uv.u) || !std::isfinite(uv.v)) return out;
  if (address_ == Address::Wrap) {
    uv.u -= std::floor(uv.u);
    uv.v -= std::floor(uv.v);
  } else {
    uv.u = std::clamp(uv.u, 0.0, 1.0);
    uv.v = std::clamp(uv.v, 0.0, 1.0);
  }
  const double s = uv.u * width - 0.5, t = (1.0 - uv.v) * height - 0.5;
  auto distance2 = [&](double di, double dj) { return di * di * du * du + dj * dj * dv * dv; };

  // A half along u keeps texels i with (i - s) * sign >= 0; along v, whose rows run against v,
  // (t - j) * sign >= 0. As bounds on the texel indices and on the refined touch (s_lo..s_hi, t_lo..t_hi).
  double s_lo = -HUGE_VAL, s_hi = HUGE_VAL, t_lo = -HUGE_VAL, t_hi = HUGE_VAL;
  if (half.axis == 0) (half.sign > 0.0 ? s_lo : s_hi) = s;
  if (half.axis == 1) (half.sign > 0.0 ? t_hi : t_lo) = t;

  // The texel under the centre gives the first touch (on the half: the nearest in it); only
  // texels that could beat it are searched.
  long long best_i = std::llround(s), best_j = std::llround(t);
  if (half.axis == 0) best_i = (long long)(half.sign > 0.0 ? std::ceil(s) : std::floor(s));
  if (half.axis == 1) best_j = (long long)(half.sign > 0.0 ? std::floor(t) : std::ceil(t));
  if (address_ == Address::Clamp) best_i = std::clamp(best_i, 0LL, (long long)width - 1), best_j = std::clamp(best_j, 0LL, (long long)height - 1);
  if (double(best_i) < s_lo || double(best_i) > s_hi || double(best_j) < t_lo || double(best_j) > t_hi) return std::nullopt;
  const double d0 = distance2(double(best_i) - s, double(best_j) - t);
  if (d0 >= r2) return out;  // texels wider than the ball: nothing to search
  double best = levels.front().at(resolveIndex(best_i, width, address_), resolveIndex(best_j, height, address_)) + std::sqrt(r2 - d0);
  const double depth = max_depth_m_, rise = std::max(0.0, std::sqrt(r2 - d0) - depth);
  const double reach2 = r2 - rise * rise;  // beyond it even the highest texel stays below the first touch
  double reach_u = std::sqrt(reach2) / du, reach_v = std::sqrt(reach2) / dv;
  // Wrapped, each texel is met once, at its nearest image; on a half, at its nearest on that side.
  if (address_ == Address::Wrap)
    reach_u = std::min(reach_u, (half.axis == 0 ? 1.0 : 0.5) * width), reach_v = std::min(reach_v, (half.axis == 1 ? 1.0 : 0.5) * height);
  long long ia = (long long)std::ceil(s - reach_u), ib = (long long)std::floor(s + reach_u);
  long long ja = (long long)std::ceil(t - reach_v), jb = (long long)std::floor(t + reach_v);
  if (address_ == Address::Clamp) {
    ia = std::max(ia, 0LL), ib = std::min(ib, (long long)width - 1);
    ja = std::max(ja, 0LL), jb = std::min(jb, (long long)height - 1);
  }
  if (half.axis == 0) (half.sign > 0.0 ? ia : ib) = best_i;
  if (half.axis == 1) (half.sign > 0.0 ? jb : ja) = best_j;

  // A texel's lift, as the search below reads one at level 0 (its nearest point is its centre).
  auto texelLift = [&](long long i, long long j, double& lift) {
    const double gi = std::max({0.0, double(i) - s, s - double(i)}), gj = std::max({0.0, double(j) - t, t - double(j)});
    const double d2 = distance2(gi, gj);
    if (d2 >= r2) return false;
    lift = levels.front().at(resolveIndex(i, width, address_), resolveIndex(j, height, address_)) + std::sqrt(r2 - d2);
    return true;
  };
  // The texel a search nearby touched, at its image nearest the centre, inside the region: no
  // block below its lift can hold the touch. Blocks at its lift are still searched, so the first
  // texel of the greatest lift in the search's order is found, as without it.
  double at_least = -HUGE_VAL;
  if (near) {
    long long i = near->i, j = near->j;
    if (address_ == Address::Wrap)
      i += (long long)width * std::llround((s - double(i)) / width), j += (long long)height * std::llround((t - double(j)) / height);
    double lift = 0.0;
    if (i >= ia && i <= ib && j >= ja && j <= jb && texelLift(i, j, lift)) at_least = lift;
  }

  // The coarsest level at which the region spans at most four blocks each way.
  int level0 = 0;
  while (level0 + 1 < int(levels.size()) && ((ib - ia + 1) >> level0) > 4) ++level0;
  while (level0 + 1 < int(levels.size()) && ((jb - ja + 1) >> level0) > 4) ++level0;

  struct Block {
    int level;
    long long i, j;  // unwrapped block indices at `level`
  };
  constexpr int kStack = 64;  // a block pushes four children: 4 per level over at most 15 levels
  Block stack[kStack];
  for (long long bj = floorDiv(ja, level0); bj <= floorDiv(jb, level0); ++bj)
    for (long long bi = floorDiv(ia, level0); bi <= floorDiv(ib, level0); ++bi) {
      int top = 0;
      stack[top++] = {level0, bi, bj};
      while (top > 0) {
        const Block b = stack[--top];
        const Level& level = levels[std::size_t(b.level)];
        const long long ilo = b.i << b.level, ihi = ilo + (1LL << b.level) - 1;
        const long long jlo = b.j << b.level, jhi = jlo + (1LL << b.level) - 1;
        if (ihi < ia || ilo > ib || jhi < ja || jlo > jb) continue;
        const double gi = std::max({0.0, double(ilo) - s, s - double(ihi)}), gj = std::max({0.0, double(jlo) - t, t - double(jhi)});
        const double d2 = distance2(gi, gj);
        if (d2 >= r2) continue;
        const double bound = level.at(resolveIndex(b.i, level.width, address_), resolveIndex(b.j, level.height, address_)) +
                             std::sqrt(r2 - d2);
        if (bound <= best || bound < at_least) continue;
        if (b.level == 0) {
          best = bound, best_i = b.i, best_j = b.j;  // a texel: its nearest point is its centre
          continue;
        }
        // Children, the farthest pushed first so that the nearest is searched first.
        Block children[4];
        double order[4];
        for (int k = 0; k < 4; ++k) {
          children[k] = {b.level - 1, 2 * b.i + (k & 1), 2 * b.j + (k >> 1)};
          const double ci = double(children[k].i << children[k].level) + 0.5 * double((1LL << children[k].level) - 1);
          const double cj = double(children[k].j << children[k].level) + 0.5 * double((1LL << children[k].level) - 1);
          order[k] = distance2(ci - s, cj - t);
        }
        for (int pass = 0; pass < 4; ++pass) {
          int far = -1;
          for (int k = 0; k < 4; ++k)
            if (order[k] >= 0.0 && (far < 0 || order[k] > order[far])) far = k;
          order[far] = -1.0;
          if (top < kStack) stack[top++] = children[far];
        }
      }
    }

  // Refined on the bilinear height: fixed-point steps towards where the ball's sphere meets the
  // surface tangentially, p = x + z grad h(p) (z the centre's height above p), each kept only if
  // it lifts the ball. Where they settle the touch is a stationary point, so the normal stays the
  // lift's gradient (the read is a potential: it neither adds nor takes energy); at an edge they
  // do not, and the touch stays at the texel centre.
  out.texel = Texel{best_i, best_j};
  double ps = double(best_i), pt = double(best_j);
  auto lifted = [&](double qs, double qt) {
    const double d2 = distance2(qs - s, qt - t);
    return d2 < r2 ? bilinear(levels.front(), qs, qt) + std::sqrt(r2 - d2) : -1e300;
  };
  double value = lifted(ps, pt);
  for (int step = 0; step < 4; ++step) {
    const double z = std::sqrt(std::max(0.0, r2 - distance2(ps - s, pt - t)));
    Eigen::Vector2d g;  // metres of height per texel
    bilinear(levels.front(), ps, pt, &g);
    const double qs = std::clamp(std::clamp(s + z * g.x() / (du * du), double(best_i) - 1.0, double(best_i) + 1.0), s_lo, s_hi);
    const double qt = std::clamp(std::clamp(t + z * g.y() / (dv * dv), double(best_j) - 1.0, double(best_j) + 1.0), t_lo, t_hi);
    double candidate = lifted(qs, qt), cs = qs, ct = qt;
    if (!(candidate > value)) {
      // Across a crest the step along it settles where the one across it does not: a ball on a
      // ridge's crest line (a V-groove's rim, read between texel centres) slides its touch along
      // the crest to the foot of its centre instead of staying at the texel centre, whose lift
      // rippled by 2.6 um a texel along a groove under a 5 mm ball.
      const double along_s = lifted(qs, pt), along_t = lifted(ps, qt);
      candidate = std::max(along_s, along_t);
      cs = along_s >= along_t ? qs : ps;
      ct = along_s >= along_t ? pt : qt;
      if (!(candidate > value)) break;
    }
    ps = cs, pt = ct, value = candidate;
  }
  const double x_u = (s - ps) * du, x_v = (pt - t) * dv;  // the centre from the touch, along u and v
  out.normal = Eigen::Vector3d(x_u, x_v, std::sqrt(std::max(0.0, r2 - x_u * x_u - x_v * x_v))) / r;
  out.lift_m = value - r;
  return out;
}

}  // namespace thx::tex
