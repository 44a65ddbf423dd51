#include "benchmarks/exact_surfaces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "benchmarks/bench_rig.hpp"

namespace thx::bench {

void ExactSurface::setSize(int size) {
  // As rasterize(): texel centres at X = (i + 0.5) d, Y = extent - (j + 0.5) d.
  const double d = extent_m_ / size;
  double top = -std::numeric_limits<double>::infinity();
  for (int j = 0; j < size; ++j) {
    const double Y = extent_m_ - (j + 0.5) * d;
    for (int i = 0; i < size; ++i) top = std::max(top, h((i + 0.5) * d, Y));
  }
  h_top_ = top;
}

// ---------------------------------------------------------------------------------------------

SineSurface::SineSurface(double amplitude_m, double period_m, double extent_m)
    : ExactSurface(extent_m), a_(amplitude_m), period_(period_m), k_(2.0 * std::numbers::pi / period_m) {}

std::string SineSurface::description() const {
  return fmt("sine: h = A sin(kx) sin(ky), A = %.2g mm, period %.3g mm (slopes up to %.0f deg)", a_ * 1e3,
             period_ * 1e3, std::atan(a_ * k_) * 180.0 / std::numbers::pi);
}

tex::GenerateRequest SineSurface::request(int size) const {
  tex::GenerateRequest r;
  r.kind = "sine";
  r.size = size;
  r.params = {{"amplitude", a_}, {"period", period_}, {"extent", extent_m_}};
  return r;
}

double SineSurface::h(double X, double Y) const { return a_ * std::sin(k_ * X) * std::sin(k_ * Y); }

Eigen::Vector3d SineSurface::closest(const Eigen::Vector3d& p) const {
  const double e2 = extent_m_ / 2;
  auto dist2 = [&](double x, double y) {
    const double dz = z(x, y) - p.z();
    return (x - p.x()) * (x - p.x()) + (y - p.y()) * (y - p.y()) + dz * dz;
  };
  // The closest point lies within the vertical distance of p, horizontally: search that square.
  const double r = std::max(z(p.x(), p.y()) - p.z(), 1e-12);
  constexpr int kGrid = 32;
  double bx = p.x(), by = p.y(), best = dist2(bx, by);
  for (int i = 0; i <= kGrid; ++i) {
    for (int j = 0; j <= kGrid; ++j) {
      const double x = p.x() - r + 2 * r * i / kGrid, y = p.y() - r + 2 * r * j / kGrid;
      const double d2 = dist2(x, y);
      if (d2 < best) {
        best = d2;
        bx = x;
        by = y;
      }
    }
  }
  // Newton on grad(D)/2 = (x - px + (g - pz) gx, y - py + (g - pz) gy) = 0, backtracking on D.
  double x = bx, y = by;
  for (int it = 0; it < 100; ++it) {
    const double sx = std::sin(k_ * (x + e2)), cx = std::cos(k_ * (x + e2));
    const double sy = std::sin(k_ * (y + e2)), cy = std::cos(k_ * (y + e2));
    const double g = a_ * sx * sy - h_top_, gx = a_ * k_ * cx * sy, gy = a_ * k_ * sx * cy;
    const double gxx = -a_ * k_ * k_ * sx * sy, gyy = gxx, gxy = a_ * k_ * k_ * cx * cy;
    const double res = g - p.z();
    const double G0 = x - p.x() + res * gx, G1 = y - p.y() + res * gy;
    const double H00 = 1 + gx * gx + res * gxx, H11 = 1 + gy * gy + res * gyy, H01 = gx * gy + res * gxy;
    const double det = H00 * H11 - H01 * H01;
    double s0 = -G0, s1 = -G1;  // gradient step if the Hessian is not positive definite
    if (H00 > 0 && det > 0) {
      s0 = -(H11 * G0 - H01 * G1) / det;
      s1 = -(-H01 * G0 + H00 * G1) / det;
    }
    if (std::hypot(s0, s1) < 1e-13) {
      x += s0;
      y += s1;
      break;
    }
    const double d_now = dist2(x, y);
    double t = 1.0;
    while (t > 1e-12 && dist2(x + t * s0, y + t * s1) > d_now) t *= 0.5;
    x += t * s0;
    y += t * s1;
    if (t * std::hypot(s0, s1) < 1e-13) break;
  }
  return {x, y, z(x, y)};
}

// ---------------------------------------------------------------------------------------------

VValleySurface::VValleySurface(double angle_deg, double period_m, double extent_m)
    : ExactSurface(extent_m),
      angle_deg_(angle_deg),
      period_(period_m),
      slope_(std::tan((90.0 - angle_deg / 2.0) * std::numbers::pi / 180.0)) {}

std::string VValleySurface::description() const {
  return fmt("vvalley: V valleys, opening %.0f deg (walls %.0f deg from the plane), period %.3g mm, depth %.3g mm",
             angle_deg_, 90.0 - angle_deg_ / 2, period_ * 1e3, slope_ * period_ / 2 * 1e3);
}

tex::GenerateRequest VValleySurface::request(int size) const {
  tex::GenerateRequest r;
  r.kind = "vvalley";
  r.size = size;
  r.params = {{"angle_deg", angle_deg_}, {"period", period_}, {"extent", extent_m_}};
  return r;
}

double VValleySurface::h(double X, double /*Y*/) const {
  const double f = X / period_ - std::floor(X / period_);
  return f < 0.5 ? -slope_ * f * period_ : -slope_ * (1.0 - f) * period_;
}

int VValleySurface::region(double x, double reach) const {
  const double X = x + extent_m_ / 2, f = X / period_ - std::floor(X / period_);  // ridge at f = 0, floor at 0.5
  if (std::fabs(f - 0.5) * period_ <= reach) return 0;
  if (std::min(f, 1.0 - f) * period_ <= reach) return 1;
  return 2;
}

namespace {

// The walls in the (X, z) cross-section near X: segments between ridges (z = top) and floors.
template <class Visit>
void forEachWall(double X, double reach, double period, double slope, double h_top, Visit&& visit) {
  const long long m0 = (long long)std::floor((X - reach) / period) - 1;
  const long long m1 = (long long)std::floor((X + reach) / period) + 1;
  for (long long m = m0; m <= m1; ++m) {
    const double x_ridge = double(m) * period, x_floor = x_ridge + period / 2, x_next = x_ridge + period;
    const double z_ridge = -h_top, z_floor = -slope * period / 2 - h_top;
    visit(x_ridge, z_ridge, x_floor, z_floor);
    visit(x_floor, z_floor, x_next, z_ridge);
  }
}

}  // namespace

Eigen::Vector3d VValleySurface::closest(const Eigen::Vector3d& p) const {
  const double e2 = extent_m_ / 2, X = p.x() + e2;
  const double reach = std::max(z(p.x(), p.y()) - p.z(), 0.0) + 1e-9;
  double best = std::numeric_limits<double>::infinity(), bx = X, bz = p.z();
  forEachWall(X, reach, period_, slope_, h_top_, [&](double x0, double z0, double x1, double z1) {
    const double dx = x1 - x0, dz = z1 - z0;
    double t = ((X - x0) * dx + (p.z() - z0) * dz) / (dx * dx + dz * dz);
    t = std::clamp(t, 0.0, 1.0);
    const double qx = x0 + t * dx, qz = z0 + t * dz;
    const double d2 = (qx - X) * (qx - X) + (qz - p.z()) * (qz - p.z());
    if (d2 < best) {
      best = d2;
      bx = qx;
      bz = qz;
    }
  });
  return {bx - e2, p.y(), bz};
}

Eigen::Vector3d VValleySurface::closestGolden(const Eigen::Vector3d& p) const {
  const double e2 = extent_m_ / 2, X = p.x() + e2;
  const double reach = std::max(z(p.x(), p.y()) - p.z(), 0.0) + 1e-9;
  auto dist2 = [&](double x) {
    const double dz = h(x, 0.0) - h_top_ - p.z();
    return (x - X) * (x - X) + dz * dz;
  };
  const double phi = (std::sqrt(5.0) - 1.0) / 2.0;
  double best = std::numeric_limits<double>::infinity(), bx = X;
  forEachWall(X, reach, period_, slope_, h_top_, [&](double x0, double, double x1, double) {
    // The distance is convex along one wall: golden-section search between its ends.
    double a = x0, b = x1;
    double c = b - phi * (b - a), d = a + phi * (b - a);
    double fc = dist2(c), fd = dist2(d);
    for (int it = 0; it < 200 && b - a > 1e-15; ++it) {
      if (fc < fd) {
        b = d;
        d = c;
        fd = fc;
        c = b - phi * (b - a);
        fc = dist2(c);
      } else {
        a = c;
        c = d;
        fc = fd;
        d = a + phi * (b - a);
        fd = dist2(d);
      }
    }
    for (double x : {x0, x1, (a + b) / 2}) {
      const double d2 = dist2(x);
      if (d2 < best) {
        best = d2;
        bx = x;
      }
    }
  });
  return {bx - e2, p.y(), h(bx, 0.0) - h_top_};
}

}  // namespace thx::bench
