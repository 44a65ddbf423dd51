#include "clients/audio/analysis/tet_element.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "base/number_text.hpp"
#include "clients/audio/analysis/modal_error.hpp"

namespace thx::audio {
namespace {

struct QuadraturePoint {
  Eigen::Vector3d xi;  // reference coordinates; barycentrics L = (1 - sum, xi, eta, zeta)
  double weight;       // reference tet volume is 1/6
};

std::vector<QuadraturePoint> centroidRule() { return {{Eigen::Vector3d::Constant(0.25), 1.0 / 6.0}}; }

std::vector<QuadraturePoint> fourPointRule() {
  const double a = 0.5854101966249685, b = 0.1381966011250105;
  return {{{b, b, b}, 1.0 / 24}, {{a, b, b}, 1.0 / 24}, {{b, a, b}, 1.0 / 24}, {{b, b, a}, 1.0 / 24}};
}

// Gauss-Legendre on the unit cube mapped to the tet by xi = u, eta = (1-u) v, zeta = (1-u)(1-v) w
// (Jacobian (1-u)^2 (1-v)): 4 x 3 x 3 points integrate degree-4 polynomials exactly.
std::vector<QuadraturePoint> collapsedCubeRule() {
  const double s4a = 0.3399810435848563, s4b = 0.8611363115940526;
  const double w4a = 0.6521451548625461, w4b = 0.3478548451374538;
  const std::array<double, 4> x4{0.5 - 0.5 * s4b, 0.5 - 0.5 * s4a, 0.5 + 0.5 * s4a, 0.5 + 0.5 * s4b};
  const std::array<double, 4> w4{0.5 * w4b, 0.5 * w4a, 0.5 * w4a, 0.5 * w4b};
  const double s3 = std::sqrt(0.6);
  const std::array<double, 3> x3{0.5 - 0.5 * s3, 0.5, 0.5 + 0.5 * s3};
  const std::array<double, 3> w3{5.0 / 18, 8.0 / 18, 5.0 / 18};
  std::vector<QuadraturePoint> rule;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        const double u = x4[i], v = x3[j], w = x3[k];
        rule.push_back({{u, (1 - u) * v, (1 - u) * (1 - v) * w}, w4[i] * w3[j] * w3[k] * (1 - u) * (1 - u) * (1 - v)});
      }
  return rule;
}

// Shape functions and their reference derivatives (rows: nodes; columns: d/dxi, d/deta, d/dzeta).
template <int NN>
void shapeFunctions(const Eigen::Vector3d& xi, Eigen::Matrix<double, NN, 1>& n, Eigen::Matrix<double, NN, 3>& dn) {
  const std::array<double, 4> l{1.0 - xi.sum(), xi.x(), xi.y(), xi.z()};
  // dL_a/dxi_c
  auto dl = [](int a, int c) { return a == 0 ? -1.0 : (a - 1 == c ? 1.0 : 0.0); };
  if constexpr (NN == 4) {
    for (int a = 0; a < 4; ++a) {
      n[a] = l[a];
      for (int c = 0; c < 3; ++c) dn(a, c) = dl(a, c);
    }
  } else {
    for (int a = 0; a < 4; ++a) {
      n[a] = l[a] * (2.0 * l[a] - 1.0);
      for (int c = 0; c < 3; ++c) dn(a, c) = (4.0 * l[a] - 1.0) * dl(a, c);
    }
    for (int e = 0; e < 6; ++e) {
      const int a = kTet10Edges[e][0], b = kTet10Edges[e][1];
      n[4 + e] = 4.0 * l[a] * l[b];
      for (int c = 0; c < 3; ++c) dn(4 + e, c) = 4.0 * (l[b] * dl(a, c) + l[a] * dl(b, c));
    }
  }
}

[[noreturn]] void degenerate(const TetMesh& mesh, std::size_t index, double det) {
  std::string corners;
  for (int a = 0; a < 4; ++a) {
    const Eigen::Vector3d& x = mesh.nodes[mesh.tets[index][a]];
    corners += (a ? " (" : "(") + numberText(x.x()) + ", " + numberText(x.y()) + ", " + numberText(x.z()) + ")";
  }
  throw ModalError(mesh.name + ": tetrahedron " + std::to_string(index) + " with corners " + corners +
                   " is degenerate or inverted (Jacobian determinant " + numberText(det) +
                   "): expected a positive volume");
}

// Fixed-size matrices throughout: no allocation per quadrature point, which keeps assembly fast
// in the unoptimised sanitizer build too.
template <int NN>
ElementMatrices elementMatricesOf(const TetMesh& mesh, std::size_t index, const Eigen::Matrix<double, 6, 6>& elasticity,
                                  double density_kg_per_m3) {
  static const std::vector<QuadraturePoint> kCentroid = centroidRule(), kFour = fourPointRule(),
                                            kCollapsed = collapsedCubeRule();
  constexpr bool kLinear = NN == 4;
  Eigen::Matrix<double, 3, NN> x;
  for (int a = 0; a < NN; ++a) x.col(a) = mesh.nodes[std::size_t(mesh.tets[index][std::size_t(a)])];
  // A determinant below this fraction of the corner tet's scale counts as degenerate.
  const Eigen::Vector3d e1 = x.col(1) - x.col(0), e2 = x.col(2) - x.col(0), e3 = x.col(3) - x.col(0);
  const double min_det = 1e-10 * e1.norm() * e2.norm() * e3.norm();

  Eigen::Matrix<double, 3 * NN, 3 * NN> k = Eigen::Matrix<double, 3 * NN, 3 * NN>::Zero();
  Eigen::Matrix<double, NN, NN> scalar_mass = Eigen::Matrix<double, NN, NN>::Zero();
  Eigen::Matrix<double, NN, 1> n;
  Eigen::Matrix<double, NN, 3> dn;
  Eigen::Matrix<double, 6, 3 * NN> b;
  double volume = 0.0;

  for (const QuadraturePoint& q : kLinear ? kCentroid : kFour) {
    shapeFunctions<NN>(q.xi, n, dn);
    const Eigen::Matrix3d jac = x * dn;  // d x / d xi
    const double det = jac.determinant();
    if (!(det > min_det)) degenerate(mesh, index, det);
    const Eigen::Matrix<double, NN, 3> g = dn * jac.inverse();  // d N / d x
    b.setZero();
    for (int a = 0; a < NN; ++a) {
      b(0, 3 * a) = g(a, 0);
      b(1, 3 * a + 1) = g(a, 1);
      b(2, 3 * a + 2) = g(a, 2);
      b(3, 3 * a + 1) = g(a, 2), b(3, 3 * a + 2) = g(a, 1);
      b(4, 3 * a) = g(a, 2), b(4, 3 * a + 2) = g(a, 0);
      b(5, 3 * a) = g(a, 1), b(5, 3 * a + 1) = g(a, 0);
    }
    const Eigen::Matrix<double, 6, 3 * NN> db = (q.weight * det) * (elasticity * b);
    k.noalias() += b.transpose() * db;
  }
  for (const QuadraturePoint& q : kLinear ? kFour : kCollapsed) {
    shapeFunctions<NN>(q.xi, n, dn);
    const double det = (x * dn).determinant();
    if (!(det > min_det)) degenerate(mesh, index, det);
    scalar_mass.noalias() += (q.weight * det * density_kg_per_m3) * (n * n.transpose());
    volume += q.weight * det;
  }
  ElementMatrices out;
  out.stiffness = k;
  out.mass = Eigen::MatrixXd::Zero(3 * NN, 3 * NN);
  for (int a = 0; a < NN; ++a)
    for (int c2 = 0; c2 < NN; ++c2)
      for (int c = 0; c < 3; ++c) out.mass(3 * a + c, 3 * c2 + c) = scalar_mass(a, c2);
  out.volume_m3 = volume;
  return out;
}

}  // namespace

ElementMatrices elementMatrices(const TetMesh& mesh, std::size_t index, const Eigen::Matrix<double, 6, 6>& elasticity,
                                double density_kg_per_m3) {
  return mesh.order == ElementOrder::Linear ? elementMatricesOf<4>(mesh, index, elasticity, density_kg_per_m3)
                                            : elementMatricesOf<10>(mesh, index, elasticity, density_kg_per_m3);
}

}  // namespace thx::audio
