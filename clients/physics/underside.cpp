#include "clients/physics/underside.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thx::phys {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Interval {
  double lo = -kInf, hi = kInf;
  bool empty() const { return lo > hi; }
};

// Where the ray o + t e_z is inside the sphere |p - c| <= r.
Interval sphereInterval(const Eigen::Vector3d& o, const Eigen::Vector3d& c, double r) {
  const double dx = o.x() - c.x(), dy = o.y() - c.y();
  const double h2 = r * r - dx * dx - dy * dy;
  if (h2 < 0.0) return {kInf, -kInf};
  const double h = std::sqrt(h2);
  return {c.z() - h, c.z() + h};
}

// Where the ray o + t e_z is inside the infinite cylinder of radius r around the line a + s u.
Interval sideInterval(const Eigen::Vector3d& o, const Eigen::Vector3d& a, const Eigen::Vector3d& u, double r) {
  const Eigen::Vector3d w = o - a;
  const Eigen::Vector3d d_perp = Eigen::Vector3d::UnitZ() - u.z() * u;
  const Eigen::Vector3d w_perp = w - w.dot(u) * u;
  const double qa = d_perp.squaredNorm();
  const double qb = w_perp.dot(d_perp);
  const double qc = w_perp.squaredNorm() - r * r;
  if (qa < kParallelSine) return qc <= 0.0 ? Interval{} : Interval{kInf, -kInf};
  const double disc = qb * qb - qa * qc;
  if (disc < 0.0) return {kInf, -kInf};
  const double root = std::sqrt(disc);
  return {(-qb - root) / qa, (-qb + root) / qa};
}

// Where the ray o + t e_z has its coordinate along unit u (measured from centre c) in [-h, h].
Interval slabInterval(const Eigen::Vector3d& o, const Eigen::Vector3d& c, const Eigen::Vector3d& u, double h) {
  const double s0 = (o - c).dot(u), ds = u.z();
  if (std::fabs(ds) < kParallelSine) return std::fabs(s0) <= h ? Interval{} : Interval{kInf, -kInf};
  const double t1 = (-h - s0) / ds, t2 = (h - s0) / ds;
  return {std::min(t1, t2), std::max(t1, t2)};
}

Interval intersect(Interval a, const Interval& b) {
  a.lo = std::max(a.lo, b.lo);
  a.hi = std::min(a.hi, b.hi);
  return a;
}

}  // namespace

Underside Underside::sphere(const Eigen::Isometry3d& pose, double r) {
  Underside s;
  s.kind = Kind::Sphere;
  s.plane_from_object = pose;
  s.radius = r;
  return s;
}
Underside Underside::box(const Eigen::Isometry3d& pose, const Eigen::Vector3d& half) {
  Underside s;
  s.kind = Kind::Box;
  s.plane_from_object = pose;
  s.half_extents = half;
  return s;
}
Underside Underside::capsule(const Eigen::Isometry3d& pose, double r, double half_length, int axis) {
  Underside s;
  s.kind = Kind::Capsule;
  s.plane_from_object = pose;
  s.radius = r;
  s.half_length = half_length;
  s.axis = axis;
  return s;
}
Underside Underside::cylinder(const Eigen::Isometry3d& pose, double r, double half_length, int axis) {
  Underside s = capsule(pose, r, half_length, axis);
  s.kind = Kind::Cylinder;
  return s;
}

std::optional<double> lowestZ(const Underside& s, double x, double y) {
  const Eigen::Vector3d c = s.plane_from_object.translation();
  if (s.kind == Underside::Kind::Sphere) return sphereLowestZ(c, s.radius, x, y);
  const Eigen::Vector3d o(x, y, 0.0);
  const Eigen::Matrix3d r = s.plane_from_object.linear();
  Interval in{kInf, -kInf};
  switch (s.kind) {
    case Underside::Kind::Sphere:
      break;  // above
    case Underside::Kind::Box: {
      in = Interval{};
      for (int k = 0; k < 3; ++k) in = intersect(in, slabInterval(o, c, r.col(k), s.half_extents[k]));
      break;
    }
    case Underside::Kind::Capsule: {
      // A capsule is the union of its side and its two end spheres; the ray enters the union at
      // the lowest entry among the pieces it hits (the side only where it lies between the caps).
      const Eigen::Vector3d u = r.col(s.axis);
      const Eigen::Vector3d a = c - s.half_length * u, b = c + s.half_length * u;
      double lowest = kInf;
      for (const Eigen::Vector3d& end : {a, b}) {
        const Interval e = sphereInterval(o, end, s.radius);
        if (!e.empty()) lowest = std::min(lowest, e.lo);
      }
      const Interval side = sideInterval(o, a, u, s.radius);
      if (!side.empty() && std::isfinite(side.lo)) {
        const double along = (o + side.lo * Eigen::Vector3d::UnitZ() - a).dot(u);
        if (along >= 0.0 && along <= 2.0 * s.half_length) lowest = std::min(lowest, side.lo);
      }
      if (lowest == kInf) return std::nullopt;
      return lowest;
    }
    case Underside::Kind::Cylinder: {
      const Eigen::Vector3d u = r.col(s.axis);
      in = intersect(sideInterval(o, c, u, s.radius), slabInterval(o, c, u, s.half_length));
      break;
    }
  }
  if (in.empty() || !std::isfinite(in.lo)) return std::nullopt;
  return in.lo;
}

int boxFaceUnder(const Underside& box, double x, double y) {
  const Eigen::Vector3d o(x, y, 0.0), c = box.plane_from_object.translation();
  double enter = -kInf, exit = kInf;
  int face = -1;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d u = box.plane_from_object.linear().col(k);
    const Interval in = slabInterval(o, c, u, box.half_extents[k]);
    if (in.empty()) return -1;
    exit = std::min(exit, in.hi);
    // Entering from below through the face whose outward normal points down: -h where the
    // axis points up.
    if (std::isfinite(in.lo) && in.lo > enter) enter = in.lo, face = 2 * k + (u.z() < 0.0 ? 1 : 0);
  }
  return enter <= exit ? face : -1;
}

Eigen::Vector3d boxFaceNormalUp(const Underside& box, int face) {
  const Eigen::Vector3d u = box.plane_from_object.linear().col(face / 2);
  return face % 2 == 1 ? Eigen::Vector3d(-u) : u;
}

Eigen::Vector3d contactOnObject(const Underside& s, const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
  const Eigen::Vector3d c = s.plane_from_object.translation();
  switch (s.kind) {
    case Underside::Kind::Sphere:
      return c - s.radius * n;
    case Underside::Kind::Box:
      return p;
    case Underside::Kind::Capsule:
    case Underside::Kind::Cylinder: {
      const Eigen::Vector3d u = s.plane_from_object.linear().col(s.axis);
      const double along = (p - c).dot(u);
      // A point on a cylinder's end face (or its rim) is on a flat part: keep it. The tolerance
      // is relative so the rim itself counts as the face.
      const bool on_side = std::fabs(along) < s.half_length * (1.0 - 1e-9);
      if (s.kind == Underside::Kind::Cylinder && !on_side) return p;
      const double clamped = std::clamp(along, -s.half_length, s.half_length);
      Eigen::Vector3d dir = n;
      if (on_side) {
        const Eigen::Vector3d across = n - n.dot(u) * u;
        // n along the axis (a standing capsule's side touching?) cannot happen for a lowest
        // point on the side; fall back to p rather than divide by ~0.
        if (across.norm() < 1e-9) return p;
        dir = across.normalized();
      }
      return c + clamped * u - s.radius * dir;
    }
  }
  return p;
}

Eigen::AlignedBox3d planeBounds(const Underside& s) {
  const Eigen::Vector3d c = s.plane_from_object.translation();
  const Eigen::Matrix3d& r = s.plane_from_object.linear();
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  switch (s.kind) {
    case Underside::Kind::Sphere:
      e.setConstant(s.radius);
      break;
    case Underside::Kind::Box:
      e = r.cwiseAbs() * s.half_extents;
      break;
    case Underside::Kind::Capsule:
      e = s.half_length * r.col(s.axis).cwiseAbs() + Eigen::Vector3d::Constant(s.radius);
      break;
    case Underside::Kind::Cylinder: {
      const Eigen::Vector3d u = r.col(s.axis);
      for (int k = 0; k < 3; ++k)
        e[k] = s.half_length * std::fabs(u[k]) + s.radius * std::sqrt(std::max(0.0, 1.0 - u[k] * u[k]));
      break;
    }
  }
  return {c - e, c + e};
}

}  // namespace thx::phys
