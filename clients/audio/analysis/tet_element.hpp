#pragma once
// Element stiffness and consistent mass of Tet4 and Tet10 elements (isoparametric).
// Stiffness: 1-point (Tet4) or 4-point degree-2 (Tet10) Gauss rule, exact on straight-sided
// elements. Mass: 4-point rule (Tet4, exact) or a collapsed-cube Gauss-Legendre rule exact for the
// degree-4 integrand of straight-sided Tet10.
// Element DOFs are node-major: (node a, axis c) -> 3a + c.
#include <Eigen/Dense>
#include <array>
#include <string>

#include "clients/audio/analysis/elastic_material.hpp"
#include "clients/audio/analysis/tet_mesh.hpp"

namespace thx::audio {

struct ElementMatrices {
  Eigen::MatrixXd stiffness;  // 3n x 3n, N/m
  Eigen::MatrixXd mass;       // 3n x 3n, kg
  double volume_m3 = 0.0;
};

// The matrices of mesh.tets[index]. Throws ModalError naming the mesh's object, the element and
// its corners if its Jacobian determinant is not positive (degenerate or inverted) anywhere the
// rules sample it.
ElementMatrices elementMatrices(const TetMesh& mesh, std::size_t index, const Eigen::Matrix<double, 6, 6>& elasticity,
                                double density_kg_per_m3);

}  // namespace thx::audio
