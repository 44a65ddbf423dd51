#include "clients/audio/analysis/modal_body.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <limits>
#include <map>
#include <span>
#include <stdexcept>

namespace thx::audio {

namespace {

// The three corners of a tet other than corner `skip`, in corner order (as the faces were always
// walked), and the same sorted (the key that finds a face's other tet).
std::array<int, 3> faceCorners(const std::array<int, 10>& t, int skip) {
  std::array<int, 3> f{};
  int n = 0;
  for (int c = 0; c < 4; ++c)
    if (c != skip) f[std::size_t(n++)] = t[std::size_t(c)];
  return f;
}

std::array<int, 3> sortedFace(const std::array<int, 10>& t, int skip) {
  std::array<int, 3> f = faceCorners(t, skip);
  std::sort(f.begin(), f.end());
  return f;
}

// Squared distance from p to an axis-aligned box (0 inside): a lower bound for anything in it.
double squaredDistanceToBox(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).squaredNorm();
}

// The point of triangle abc nearest to p (Ericson, Real-Time Collision Detection, §5.1.5).
Eigen::Vector3d closestOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                  const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

}  // namespace

ModalBody::ModalBody(TetMesh mesh, AudibleModes modes) : mesh_(std::move(mesh)), modes_(std::move(modes)) {
  if (modes_.size() > 0 && modes_.shapes.rows() != mesh_.dofCount())
    throw std::logic_error("ModalBody " + mesh_.name + ": mode shapes have " + std::to_string(modes_.shapes.rows()) +
                                " rows, the mesh " + std::to_string(mesh_.dofCount()) + " DOFs");
  inverse_.reserve(mesh_.tets.size());
  tet_boxes_.reserve(mesh_.tets.size());
  auto boxOf = [&](std::span<const int> corners, double pad) {
    Box b{mesh_.nodes[std::size_t(corners[0])], mesh_.nodes[std::size_t(corners[0])]};
    for (int c : corners) b.lo = b.lo.cwiseMin(mesh_.nodes[std::size_t(c)]), b.hi = b.hi.cwiseMax(mesh_.nodes[std::size_t(c)]);
    const double margin = pad * (b.hi - b.lo).maxCoeff();
    b.lo.array() -= margin;
    b.hi.array() += margin;
    return b;
  };
  std::map<std::array<int, 3>, int> face_count;
  for (const auto& t : mesh_.tets) {
    Eigen::Matrix3d e;
    for (int c = 0; c < 3; ++c) e.col(c) = mesh_.nodes[std::size_t(t[std::size_t(c + 1)])] - mesh_.nodes[std::size_t(t[0])];
    inverse_.push_back(e.inverse());
    tet_boxes_.push_back(boxOf(std::span<const int>(t.data(), 4), 1e-9));
    for (int skip = 0; skip < 4; ++skip) ++face_count[sortedFace(t, skip)];
  }
  for (std::size_t k = 0; k < mesh_.tets.size(); ++k)
    for (int skip = 0; skip < 4; ++skip) {
      if (face_count[sortedFace(mesh_.tets[k], skip)] != 1) continue;
      Face f{int(k), faceCorners(mesh_.tets[k], skip), {}};
      f.box = boxOf(f.corners, 0.0);
      boundary_.push_back(f);
    }
}


ModalBody::Location ModalBody::locate(const Eigen::Vector3d& point) const {
  auto barycentric = [&](std::size_t k, const Eigen::Vector3d& x) {
    const Eigen::Vector3d b = inverse_[k] * (x - mesh_.nodes[std::size_t(mesh_.tets[k][0])]);
    return Eigen::Vector4d(1.0 - b.sum(), b.x(), b.y(), b.z());
  };
  Location at;
  for (std::size_t k = 0; k < mesh_.tets.size(); ++k) {
    if (squaredDistanceToBox(point, tet_boxes_[k].lo, tet_boxes_[k].hi) > 0.0) continue;
    const Eigen::Vector4d bary = barycentric(k, point);
    if (bary.minCoeff() >= -1e-12) {  // inside (or on a face): the first such tet will do
      at.tet = int(k);
      at.barycentric = bary.cwiseMax(0.0) / bary.cwiseMax(0.0).sum();
      return at;
    }
  }
  // Outside: the nearest point of the mesh, which lies on a boundary face (the first nearest in
  // tet order); a face whose box is no nearer than the best so far cannot win.
  at.inside = false;
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d nearest = point;
  for (const Face& f : boundary_) {
    if (squaredDistanceToBox(point, f.box.lo, f.box.hi) >= best) continue;
    const Eigen::Vector3d q = closestOnTriangle(point, mesh_.nodes[std::size_t(f.corners[0])],
                                                mesh_.nodes[std::size_t(f.corners[1])],
                                                mesh_.nodes[std::size_t(f.corners[2])]);
    const double d = (q - point).squaredNorm();
    if (d < best) best = d, nearest = q, at.tet = f.tet;
  }
  const Eigen::Vector4d bary = barycentric(std::size_t(at.tet), nearest).cwiseMax(0.0);
  at.barycentric = bary / bary.sum();
  return at;
}

ModalBody::Weights ModalBody::weightsAt(const Eigen::Vector3d& point) const {
  Weights w;
  if (mesh_.tets.empty()) return w;
  const Location at = locate(point);
  const auto& t = mesh_.tets[std::size_t(at.tet)];
  const Eigen::Vector4d& L = at.barycentric;
  // Shape functions of the element at L: Tet4 the barycentric coordinates; Tet10 corners
  // L(2L - 1) and edge midpoints 4 L_a L_b (tet_mesh.hpp's node order).
  if (mesh_.order == ElementOrder::Linear) {
    for (int c = 0; c < 4; ++c) w.weights[c] = L[c];
    w.count = 4;
  } else {
    for (int c = 0; c < 4; ++c) w.weights[c] = L[c] * (2.0 * L[c] - 1.0);
    for (int e = 0; e < 6; ++e) w.weights[4 + e] = 4.0 * L[kTet10Edges[std::size_t(e)][0]] * L[kTet10Edges[std::size_t(e)][1]];
    w.count = 10;
  }
  for (int c = 0; c < w.count; ++c) w.nodes[c] = t[std::size_t(c)];
  return w;
}

void ModalBody::gainsAt(const Eigen::Vector3d& point, const Eigen::Vector3d& direction, std::span<double> gains) const {
  std::fill(gains.begin(), gains.end(), 0.0);
  if (modes_.size() == 0 || mesh_.tets.empty()) return;
  const Weights w = weightsAt(point);
  const std::size_t n = std::min(gains.size(), modes_.size());
  for (int c = 0; c < w.count; ++c) {
    const Eigen::Index row = 3 * Eigen::Index(w.nodes[c]);
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Index col = Eigen::Index(i);
      gains[i] += w.weights[c] * (modes_.shapes(row, col) * direction.x() + modes_.shapes(row + 1, col) * direction.y() +
                                  modes_.shapes(row + 2, col) * direction.z());
    }
  }
}

std::vector<double> ModalBody::gainsAt(const Eigen::Vector3d& point, const Eigen::Vector3d& direction) const {
  std::vector<double> g(modes_.size());
  gainsAt(point, direction, g);
  return g;
}

}  // namespace thx::audio
