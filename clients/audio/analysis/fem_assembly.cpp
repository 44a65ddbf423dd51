#include "clients/audio/analysis/fem_assembly.hpp"

#include "clients/audio/analysis/tet_element.hpp"

namespace thx::audio {

AssembledSystem assemble(const TetMesh& mesh, const ElasticMaterial& material) {
  checkMaterial(mesh.name, material);
  AssembledSystem sys;
  sys.free_dof.assign(std::size_t(mesh.dofCount()), -1);
  for (std::size_t node = 0; node < mesh.nodes.size(); ++node)
    if (!(node < mesh.clamped.size() && mesh.clamped[node]))
      for (int c = 0; c < 3; ++c) sys.free_dof[3 * node + c] = sys.free_count++;

  const Eigen::Matrix<double, 6, 6> d = elasticityMatrix(material);
  const int nn = mesh.nodesPerTet();
  std::vector<Eigen::Triplet<double>> k_entries, m_entries;
  const std::size_t per_tet = std::size_t(9) * nn * nn;
  k_entries.reserve(per_tet * mesh.tets.size());
  m_entries.reserve(per_tet * mesh.tets.size() / 3);
  std::vector<int> rows(std::size_t(3 * nn));
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const ElementMatrices e = elementMatrices(mesh, t, d, material.density_kg_per_m3);
    sys.volume_m3 += e.volume_m3;
    for (int a = 0; a < nn; ++a)
      for (int c = 0; c < 3; ++c) rows[3 * a + c] = sys.free_dof[3 * std::size_t(mesh.tets[t][a]) + c];
    for (int i = 0; i < 3 * nn; ++i) {
      if (rows[i] < 0) continue;
      for (int j = 0; j < 3 * nn; ++j) {
        if (rows[j] < 0) continue;
        k_entries.emplace_back(rows[i], rows[j], e.stiffness(i, j));
        // The mass couples only equal axes.
        if (i % 3 == j % 3) m_entries.emplace_back(rows[i], rows[j], e.mass(i, j));
      }
    }
  }
  sys.stiffness.resize(sys.free_count, sys.free_count);
  sys.mass.resize(sys.free_count, sys.free_count);
  sys.stiffness.setFromTriplets(k_entries.begin(), k_entries.end());
  sys.mass.setFromTriplets(m_entries.begin(), m_entries.end());
  return sys;
}

}  // namespace thx::audio
