// Bad input to the modal analysis gets an error naming the object and the cause; the cache
// returns what was solved and survives a damaged file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "clients/audio/analysis/modal_analysis.hpp"
#include "clients/audio/analysis/modal_cache.hpp"
#include "clients/audio/analysis/modal_error.hpp"
#include "tests/audio/modal_fixtures.hpp"
#include "tests/support/error_text.hpp"

namespace thx::audio::test_modal_errors {
namespace {

using test::steel;

std::string errorOf(const TetMesh& mesh, const ElasticMaterial& m, const ModalSettings& s = {}) {
  return thx::test::errorOf([&] { analyse(mesh, m, s); });
}

TetMesh smallBox(const std::string& name) { return boxMesh(name, {0.1, 0.05, 0.02}, {4, 2, 1}, ElementOrder::Quadratic); }

TEST(ModalErrors, IncompressibleMaterialIsRefusedWithTheObjectAndMaterialNamed) {
  ElasticMaterial m = steel();
  m.poisson_ratio = 0.5;
  const std::string e = errorOf(smallBox("lid"), m);
  EXPECT_NE(e.find("lid"), std::string::npos) << e;
  EXPECT_NE(e.find("steel"), std::string::npos) << e;
  EXPECT_NE(e.find("Poisson ratio 0.5"), std::string::npos) << e;
}

TEST(ModalErrors, DegenerateTetIsRefusedWithItsIndexAndCorners) {
  TetMesh mesh = boxMesh("wedge", {0.1, 0.05, 0.02}, {2, 1, 1}, ElementOrder::Linear);
  // Move a node of tet 3 onto the plane of its other three corners.
  const auto& t = mesh.tets[3];
  mesh.nodes[t[3]] = (mesh.nodes[t[0]] + mesh.nodes[t[1]] + mesh.nodes[t[2]]) / 3.0;
  const std::string e = errorOf(mesh, steel());
  EXPECT_NE(e.find("wedge: tetrahedron "), std::string::npos) << e;
  EXPECT_NE(e.find("degenerate"), std::string::npos) << e;
}

TEST(ModalErrors, SolveThatDoesNotConvergeSaysSo) {
  ModalSettings s;
  s.elastic_modes = 40;
  s.max_iterations = 1;
  s.tolerance = 1e-15;
  s.lanczos_vectors = 50;
  const std::string e = errorOf(smallBox("bell"), steel(), s);
  EXPECT_NE(e.find("bell: eigen solve did not converge"), std::string::npos) << e;
}

TEST(ModalErrors, TwoSeparateBodiesHaveTwelveRigidModesAndAreRefused) {
  TetMesh a = smallBox("pair"), b = smallBox("pair");
  const int offset = int(a.nodes.size());
  for (Eigen::Vector3d x : b.nodes) a.nodes.push_back(x + Eigen::Vector3d(1, 0, 0));
  for (auto t : b.tets) {
    for (int& n : t) n += offset;
    a.tets.push_back(t);
  }
  a.clamped.resize(a.nodes.size(), 0);
  ModalSettings s;
  s.elastic_modes = 8;
  const std::string e = errorOf(a, steel(), s);
  EXPECT_NE(e.find("pair: 12 modes below 1 Hz"), std::string::npos) << e;
  EXPECT_NE(e.find("expected 6"), std::string::npos) << e;
}

class ModalCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("thx_modal_cache_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  // Six modes of the small box through the cache in this test's folder.
  ModalSolution solve(const ElasticMaterial& m = steel(), int modes = 6,
                      std::function<void(const std::string&)> progress = {}) {
    AnalysisOptions o;
    o.cache_dir = dir_.string();
    o.progress = std::move(progress);
    ModalSettings s;
    s.elastic_modes = modes;
    return analyse(smallBox("bar"), m, s, o);
  }
  std::filesystem::path dir_;
};

TEST_F(ModalCacheTest, SecondAnalysisIsReadFromTheCacheUnchanged) {
  const ModalSolution first = solve();
  EXPECT_FALSE(first.from_cache);
  const ModalSolution second = solve();
  EXPECT_TRUE(second.from_cache);
  EXPECT_EQ(second.cache_file, first.cache_file);
  EXPECT_EQ(second.omega_rad_per_s, first.omega_rad_per_s);
  EXPECT_EQ(second.shapes, first.shapes);
  EXPECT_EQ(second.rigid_modes, 6);
  // Another material or solver setting is another key.
  ElasticMaterial glass = *scene::findMaterial("glass");
  EXPECT_FALSE(solve(glass).from_cache);
  EXPECT_FALSE(solve(steel(), 7).from_cache);
}

TEST_F(ModalCacheTest, DamagedFileIsReportedAndSolvedAgain) {
  const ModalSolution first = solve();
  {
    std::fstream f(first.cache_file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(100);
    f.put('\x7f');
  }
  std::string warning;
  const ModalSolution again = solve(steel(), 6, [&](const std::string& line) {
    if (line.find("checksum") != std::string::npos) warning = line;
  });
  EXPECT_FALSE(again.from_cache);
  EXPECT_NE(warning.find(first.cache_file), std::string::npos) << warning;
  EXPECT_EQ(again.omega_rad_per_s, first.omega_rad_per_s);
}

}  // namespace
}  // namespace thx::audio::test_modal_errors
