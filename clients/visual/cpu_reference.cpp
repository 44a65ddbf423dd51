#include "clients/visual/cpu_reference.hpp"

#include <cmath>
#include <limits>

namespace thx::visual {
namespace {

// A point's continuous coordinates on the grid of texel centres: cell (floor(s), floor(t)) has
// the centres of texels (i, j), (i+1, j), (i, j+1), (i+1, j+1) at its corners.
struct GridPoint {
  double s, t;
};

GridPoint gridOf(const tex::TexturedSurface& surface, const Eigen::Vector3d& p_local) {
  const tex::TexCoord uv = surface.mapping().uvOfLocal(p_local.head<2>());
  return {tex::texelS(surface.map(), uv.u), tex::texelT(surface.map(), uv.v)};
}

// The smallest tau in [lo, hi] where c0 + c1 tau + c2 tau^2 >= 0, given that it is < 0 at lo.
std::optional<double> firstNonNegative(double c0, double c1, double c2, double lo, double hi) {
  const auto g = [&](double tau) { return c0 + tau * (c1 + tau * c2); };
  double best = std::numeric_limits<double>::infinity();
  const auto consider = [&](double tau) {
    if (tau >= lo && tau <= hi && tau < best) best = tau;
  };
  const double scale = std::fabs(c0) + std::fabs(c1) + std::fabs(c2);
  if (std::fabs(c2) <= 1e-14 * scale) {
    if (c1 != 0.0) consider(-c0 / c1);
  } else {
    const double disc = c1 * c1 - 4 * c2 * c0;
    if (disc >= 0) {
      const double q = -0.5 * (c1 + std::copysign(std::sqrt(disc), c1));
      if (q != 0.0) consider(c0 / q);
      consider(q / c2);
    }
  }
  if (!std::isfinite(best)) {
    if (g(hi) >= 0) return hi;  // rounding at a tangent root
    return std::nullopt;
  }
  return best;
}

}  // namespace

std::optional<double> firstReliefCrossing(const tex::TexturedSurface& surface, const Eigen::Vector3d& a_local,
                                          const Eigen::Vector3d& b_local) {
  const tex::TextureMap& map = surface.map();
  const tex::Address address = surface.sampling().address;
  const GridPoint ga = gridOf(surface, a_local), gb = gridOf(surface, b_local);
  const double da = -a_local.z(), db = -b_local.z();  // the ray's depth below the plane
  const double ds = gb.s - ga.s, dt = gb.t - ga.t;

  // The walk on the centre grid: shifting (u, v) by half a texel makes "the texel containing"
  // the cell between centres. It returns wrapped cells; consecutive cells differ by one step, so
  // the unwrapped index is rebuilt from the steps.
  const tex::TexCoord shift{-0.5 / map.width(), 0.5 / map.height()};
  tex::TexCoord ua = surface.mapping().uvOfLocal(a_local.head<2>()), ub = surface.mapping().uvOfLocal(b_local.head<2>());
  ua.u += shift.u, ua.v += shift.v, ub.u += shift.u, ub.v += shift.v;
  long long ci = (long long)std::floor(ga.s), cj = (long long)std::floor(ga.t);
  tex::TexelIndex previous{-1, -1};
  std::optional<double> found;
  const auto unwrapStep = [](int now, int before, int n) {
    int d = now - before;
    if (d > 1) d -= n;
    if (d < -1) d += n;
    return d;
  };
  tex::walkTexels(map, ua, ub, tex::Address::Wrap, [&](tex::TexelIndex cell) {
    if (previous.i >= 0) {
      ci += unwrapStep(cell.i, previous.i, map.width());
      cj += unwrapStep(cell.j, previous.j, map.height());
    }
    previous = cell;
    // The part of the segment inside this cell.
    double lo = 0.0, hi = 1.0;
    const auto clip = [&](double start, double delta, double cell_lo) {
      if (delta == 0.0) return;
      double t0 = (cell_lo - start) / delta, t1 = (cell_lo + 1 - start) / delta;
      if (t0 > t1) std::swap(t0, t1);
      lo = std::max(lo, t0), hi = std::min(hi, t1);
    };
    clip(ga.s, ds, double(ci));
    clip(ga.t, dt, double(cj));
    if (lo > hi) return true;  // touched at a corner only
    const auto d = [&](long long i, long long j) {
      return double(map.depth(tex::resolveIndex(i, map.width(), address), tex::resolveIndex(j, map.height(), address)));
    };
    const double d00 = d(ci, cj), d10 = d(ci + 1, cj), d01 = d(ci, cj + 1), d11 = d(ci + 1, cj + 1);
    const double a1 = d10 - d00, a2 = d01 - d00, a3 = d00 - d10 - d01 + d11;
    const double px = ga.s - double(ci), py = ga.t - double(cj);
    // surface depth along the segment: D0 + D1 tau + D2 tau^2; g = ray depth - surface depth.
    const double D0 = d00 + a1 * px + a2 * py + a3 * px * py;
    const double D1 = a1 * ds + a2 * dt + a3 * (px * dt + py * ds);
    const double D2 = a3 * ds * dt;
    const double c0 = da - D0, c1 = (db - da) - D1, c2 = -D2;
    const double g_lo = c0 + lo * (c1 + lo * c2);
    if (g_lo >= 0) {
      found = lo;
      return false;
    }
    found = firstNonNegative(c0, c1, c2, lo, hi);
    return !found;
  });
  return found;
}

std::optional<ReferenceHit> referenceHit(const tex::TexturedSurface& surface, const Ray& ray_world, bool relief,
                                         const ReferenceLight& light) {
  const Eigen::Vector3d o = surface.toLocal(ray_world.origin), dir = surface.directionToLocal(ray_world.direction);
  if (dir.z() >= 0 || o.z() <= 0) return std::nullopt;
  const Eigen::Vector3d entry = o + dir * (-o.z() / dir.z());
  const Eigen::Vector2d half = surface.mapping().size_m / 2;
  if (std::fabs(entry.x()) > half.x() || std::fabs(entry.y()) > half.y()) return std::nullopt;

  ReferenceHit hit;
  hit.p_local = entry;
  const Eigen::Vector3d& l = light.towards_light_local;
  if (relief && surface.usesRelief()) {
    const double max_depth = surface.map().maxDepth();
    const Eigen::Vector3d exit = entry + dir * (max_depth / -dir.z());
    const std::optional<double> f = firstReliefCrossing(surface, entry, exit);
    hit.p_local = entry + (exit - entry) * f.value_or(1.0);
    const Eigen::Vector3d from = hit.p_local + l * (max_depth * 1e-4);
    // A hit whose start point is already above the plane is lit: nothing of the relief rises
    // above z = 0 (a hit on a plateau at depth 0 lands a rounding error below it).
    if (light.shadows && l.z() > 0 && from.z() < 0) {
      // From just above the hit towards the light, until the ray rises out of the relief.
      const Eigen::Vector3d to = hit.p_local + l * (-hit.p_local.z() / l.z());
      hit.shadowed = firstReliefCrossing(surface, from, to).has_value();
    }
  }
  const tex::SurfacePoint sp = surface.at(hit.p_local.x(), hit.p_local.y());
  hit.uv = sp.uv;
  hit.texel = tex::texelOf(surface.map(), sp.uv, surface.sampling().address);
  hit.intensity = hit.shadowed ? 0.0 : std::max(0.0, sp.n_local.dot(l));
  return hit;
}

}  // namespace thx::visual
