#include "benchmarks/exact_curved_surfaces.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace thx::bench {
namespace {

constexpr double kRadius = 0.1 / M_PI;  // circumference 0.2 m
constexpr double kSineAmplitude = 0.5e-3, kSinePeriod = 0.01;
constexpr double kGrooveSlope = 1.0, kGroovePeriod = 0.002;  // 45-degree walls, 1 mm deep

double sineField(double X, double Y) {
  const double k = 2 * M_PI / kSinePeriod;
  return kSineAmplitude * std::sin(k * X) * std::sin(k * Y);
}
// 0 on the ridges (X = m period), -slope x the distance to the nearest ridge between them.
double grooveField(double X) {
  const double m = X / kGroovePeriod;
  return -kGrooveSlope * kGroovePeriod * std::fabs(m - std::round(m));
}

class Sphere : public CurvedSurface {
 public:
  explicit Sphere(std::string field) : CurvedSurface("sphere", std::move(field), kRadius, {2 * M_PI * kRadius, M_PI * kRadius}) {}
  Eigen::Vector3d base(double X, double Y) const override { return radius_m_ * normal(X, Y); }
  Eigen::Vector3d normal(double X, double Y) const override {
    const double phi = X / radius_m_, theta = Y / radius_m_;
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), -std::cos(theta)};
  }
  Eigen::Vector2d paramsOf(const Eigen::Vector3d& p) const override {
    double phi = std::atan2(p.y(), p.x());
    if (phi < 0) phi += 2 * M_PI;
    return {phi * radius_m_, std::acos(std::clamp(-p.z() / p.norm(), -1.0, 1.0)) * radius_m_};
  }
  Eigen::Vector3d closest(const Eigen::Vector3d& p) const override { return newtonClosest(p); }
  mesh::GeneratedMesh tessellate(int triangles) const override {
    const int rings = std::max(3, int(std::lround(std::sqrt(triangles / 4.0))));
    return mesh::sphere(radius_m_, 2 * rings, rings, 2 * M_PI * radius_m_);
  }
  // Latitudes within 45 degrees of the equator: the bumps fade toward the poles (below).
  Eigen::Vector4d probeRange() const override {
    return {0.0, extent_m_.x(), M_PI / 4 * radius_m_, 3 * M_PI / 4 * radius_m_};
  }

 private:
  // The sine times sin^2 of the polar angle: toward a pole the meridians converge, and the bumps,
  // crowded there in longitude, would grow too steep for a normal map to hold.
  double h(double X, double Y) const override {
    const double s = std::sin(Y / radius_m_);
    return sineField(X, Y) * s * s;
  }
};

class Cylinder : public CurvedSurface {
 public:
  // The map covers the circumference (0.2 m) and 0.2 m of height; the mesh is 0.1 m high.
  explicit Cylinder(std::string field) : CurvedSurface("cylinder", std::move(field), kRadius, {2 * M_PI * kRadius, 2 * M_PI * kRadius}) {}
  static constexpr double kHeight = 0.1;
  Eigen::Vector3d base(double X, double Y) const override {
    const double phi = X / radius_m_;
    return {radius_m_ * std::cos(phi), radius_m_ * std::sin(phi), Y};
  }
  Eigen::Vector3d normal(double X, double) const override {
    const double phi = X / radius_m_;
    return {std::cos(phi), std::sin(phi), 0.0};
  }
  Eigen::Vector2d paramsOf(const Eigen::Vector3d& p) const override {
    double phi = std::atan2(p.y(), p.x());
    if (phi < 0) phi += 2 * M_PI;
    return {phi * radius_m_, p.z()};
  }
  Eigen::Vector3d closest(const Eigen::Vector3d& p) const override {
    if (field_ == "sine") return newtonClosest(p);
    // Grooves along the axis: the closest point keeps p's height; around, the cross-section's
    // walls are searched piece by piece (kinks every half period) within a period of p's angle.
    const double X0 = paramsOf(p).x(), half = kGroovePeriod / 2;
    const Eigen::Vector2d q(p.x(), p.y());
    auto d2 = [&](double X) { return (base(X, 0.0).head<2>() + z(X, 0.0) * normal(X, 0.0).head<2>() - q).squaredNorm(); };
    double best_x = X0, best = d2(X0);
    const double first = std::floor((X0 - kGroovePeriod) / half) * half;
    for (double a = first; a < X0 + kGroovePeriod; a += half) {
      double lo = a, hi = a + half;
      const double g = (std::sqrt(5.0) - 1) / 2;
      for (int it = 0; it < 200 && hi - lo > 1e-14; ++it) {
        const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
        if (d2(m1) < d2(m2)) {
          hi = m2;
        } else {
          lo = m1;
        }
      }
      for (double X : {a, a + half, 0.5 * (lo + hi)}) {
        if (d2(X) < best) best = d2(X), best_x = X;
      }
    }
    return surface(best_x, p.z());
  }
  mesh::GeneratedMesh tessellate(int triangles) const override {
    // Square quads: segments around 2x the rows along the 0.1 m (the circumference is 0.2 m).
    const int rows = std::max(1, int(std::lround(std::sqrt(triangles / 4.0))));
    return mesh::cylinder(radius_m_, kHeight, 2 * rows, rows, 2 * M_PI * radius_m_);
  }
  Eigen::Vector4d probeRange() const override { return {0.0, extent_m_.x(), 0.02, 0.08}; }

 private:
  double h(double X, double Y) const override { return field_ == "sine" ? sineField(X, Y) : grooveField(X); }
};

}  // namespace

std::string CurvedSurface::description() const {
  const std::string where = shape_ == "sphere" ? "a sphere of radius " : "a cylinder of radius ";
  const std::string what = field_ == "sine" ? "sine bumps (0.5 mm amplitude, 10 mm period" +
                                                  std::string(shape_ == "sphere" ? ", fading toward the poles)" : ")")
                                            : "V-grooves along the axis (45-degree walls, 2 mm period, 1 mm deep)";
  return what + " on " + where + std::to_string(radius_m_ * 1000).substr(0, 5) + " mm";
}

Eigen::Vector3d CurvedSurface::newtonClosest(const Eigen::Vector3d& p) const {
  const Eigen::Vector2d x0 = paramsOf(p);
  auto f = [&](const Eigen::Vector2d& x) { return (surface(x.x(), x.y()) - p).squaredNorm(); };
  // The best point of a grid over a period around the radial projection, then Newton on f with
  // finite-difference derivatives and a backtracking step.
  Eigen::Vector2d x = x0;
  double fx = f(x);
  constexpr int kGrid = 40;
  for (int i = -kGrid; i <= kGrid; ++i) {
    for (int j = -kGrid; j <= kGrid; ++j) {
      const Eigen::Vector2d c = x0 + Eigen::Vector2d(i, j) * (0.6 * kSinePeriod / kGrid);
      const double fc = f(c);
      if (fc < fx) fx = fc, x = c;
    }
  }
  const double e = 1e-6;
  for (int it = 0; it < 60; ++it) {
    Eigen::Vector2d g;
    Eigen::Matrix2d H;
    for (int a = 0; a < 2; ++a) {
      Eigen::Vector2d da = Eigen::Vector2d::Zero();
      da[a] = e;
      g[a] = (f(x + da) - f(x - da)) / (2 * e);
      for (int b = 0; b < 2; ++b) {
        Eigen::Vector2d db = Eigen::Vector2d::Zero();
        db[b] = e;
        H(a, b) = (f(x + da + db) - f(x + da - db) - f(x - da + db) + f(x - da - db)) / (4 * e * e);
      }
    }
    Eigen::Vector2d step = -H.ldlt().solve(g);
    if (!step.allFinite() || g.dot(step) >= 0) step = -g * 1e-3;
    double t = 1.0;
    while (t > 1e-6 && f(x + t * step) > fx) t *= 0.5;
    const Eigen::Vector2d next = x + t * step;
    const double fn = f(next);
    if (fn > fx) break;
    const bool done = (next - x).norm() < 1e-14;
    x = next;
    fx = fn;
    if (done) break;
  }
  return surface(x.x(), x.y());
}

tex::TextureMap CurvedSurface::bake(int width, int height) {
  auto centre = [&](int i, int j) {
    return Eigen::Vector2d((i + 0.5) / width * extent_m_.x(), (1.0 - (j + 0.5) / height) * extent_m_.y());
  };
  h_top_ = -1e9;
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) h_top_ = std::max(h_top_, h(centre(i, j).x(), centre(i, j).y()));
  double max_depth = 0.0;
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) max_depth = std::max(max_depth, -z(centre(i, j).x(), centre(i, j).y()));
  tex::TextureMap map(width, height, tex::Representation::Relief, std::max(max_depth, 1e-9));
  const double e = 1e-7;
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      const Eigen::Vector2d c = centre(i, j);
      const Eigen::Vector3d t = base(c.x() + e, c.y()) - base(c.x() - e, c.y());
      Eigen::Vector3d n_local(0, 0, 1);
      if (t.norm() > 1e-12) {  // zero at a sphere's pole
        // The depth's slopes per metre of the smooth surface along its tangent and bitangent: a
        // relief map's normals are the gradient of its own depth, so its texel planes meet where
        // the depth bends (a ridge's two walls exactly at the ridge). The displaced surface's 3D
        // normal differs by the factor R / (R + z) at depth z (the walls converge with the
        // normals), which would move a ridge by (texel lever) x z / R on a flat chart.
        const double lt = t.norm();
        const double lb = (base(c.x(), c.y() + e) - base(c.x(), c.y() - e)).norm();
        const double gx = (z(c.x() + e, c.y()) - z(c.x() - e, c.y())) / lt;
        const double gy = (z(c.x(), c.y() + e) - z(c.x(), c.y() - e)) / lb;
        n_local = Eigen::Vector3d(-gx, -gy, 1.0).normalized();
      }
      map.setNormal(i, j, n_local.cast<float>());
      map.setDepth(i, j, -z(c.x(), c.y()));
    }
  }
  map.meta().kind = name();
  map.meta().extent_x_m = extent_m_.x();
  map.meta().extent_y_m = extent_m_.y();
  return map;
}

std::unique_ptr<CurvedSurface> makeCurvedSurface(const std::string& shape, const std::string& field) {
  if (field != "sine" && field != "vgrooves") throw std::runtime_error("unknown height field '" + field + "'");
  if (shape == "sphere") {
    if (field != "sine") throw std::runtime_error("the sphere carries sine bumps only");
    return std::make_unique<Sphere>(field);
  }
  if (shape == "cylinder") return std::make_unique<Cylinder>(field);
  throw std::runtime_error("unknown shape '" + shape + "'");
}

}  // namespace thx::bench
