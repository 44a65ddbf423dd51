// The built-in meshes (meshes/mesh_generators.hpp): closed and consistently wound where the shape
// is, on the shape they stand for, texture coordinates at the stated scale with whole tiles
// around every closed loop, and clear errors for impossible shapes.
#include <gtest/gtest.h>

#include <cmath>

#include "base/error.hpp"
#include "meshes/mesh_check.hpp"
#include "meshes/mesh_generators.hpp"

namespace test_mesh_generators {

using namespace thx::mesh;

MeshLimits closed() {
  MeshLimits l;
  l.require_closed = true;
  return l;
}

// Sum over triangles of (centroid . area-weighted normal) / 3: the enclosed volume, positive when
// every triangle faces outward (divergence theorem).
double enclosedVolume(const TexturedMesh& m) {
  double v = 0.0;
  for (const Triangle& t : m.triangles) {
    v += m.positions[t[0]].dot(m.positions[t[1]].cross(m.positions[t[2]])) / 6.0;
  }
  return v;
}

TEST(MeshGenerators, ClosedShapesAreClosedAndFaceOutward) {
  const GeneratedMesh s = sphere(0.05, 48, 24, 0.01);
  EXPECT_NO_THROW(checkMesh(s.mesh, closed()));
  EXPECT_NEAR(enclosedVolume(s.mesh), 4.0 / 3 * M_PI * std::pow(0.05, 3), 0.02 * 4.0 / 3 * M_PI * std::pow(0.05, 3));
  const GeneratedMesh t = torus(0.05, 0.01, 48, 16, 0.01);
  EXPECT_NO_THROW(checkMesh(t.mesh, closed()));
  EXPECT_NEAR(enclosedVolume(t.mesh), 2 * M_PI * M_PI * 0.05 * 0.01 * 0.01, 0.03 * 2 * M_PI * M_PI * 0.05 * 1e-4);
  const GeneratedMesh b = box({0.04, 0.03, 0.001}, 0.005, 0.01);
  EXPECT_NO_THROW(checkMesh(b.mesh, closed()));
  EXPECT_NEAR(enclosedVolume(b.mesh), 0.04 * 0.03 * 0.001, 1e-15);
  const GeneratedMesh room = box({0.04, 0.04, 0.04}, 0.01, 0.01, true);
  EXPECT_NO_THROW(checkMesh(room.mesh, closed()));
  EXPECT_NEAR(enclosedVolume(room.mesh), -0.04 * 0.04 * 0.04, 1e-15);  // faces in
  const GeneratedMesh bowl = lathe(bowlProfile(0.06, 0.04, 0.004, 24), 48, 0.01);
  EXPECT_NO_THROW(checkMesh(bowl.mesh, closed()));
  EXPECT_GT(enclosedVolume(bowl.mesh), 0.0);
  const GeneratedMesh vase = lathe(vaseProfile(0.2, 0.06, 0.004, 32), 48, 0.02);
  EXPECT_NO_THROW(checkMesh(vase.mesh, closed()));
  EXPECT_GT(enclosedVolume(vase.mesh), 0.0);
}

TEST(MeshGenerators, OpenTubeHasItsEndsOpen) {
  const GeneratedMesh c = cylinder(0.02, 0.05, 32, 6, 0.01);
  EXPECT_NO_THROW(checkMesh(c.mesh));
  EXPECT_THROW(checkMesh(c.mesh, closed()), thx::Error);
  for (const Eigen::Vector3d& p : c.mesh.positions) EXPECT_NEAR(p.head<2>().norm(), 0.02, 1e-15);
}

TEST(MeshGenerators, VerticesLieOnTheShape) {
  const GeneratedMesh s = sphere(0.05, 32, 16, 0.01);
  for (const Eigen::Vector3d& p : s.mesh.positions) EXPECT_NEAR(p.norm(), 0.05, 1e-15);
  const GeneratedMesh t = torus(0.05, 0.01, 32, 12, 0.01);
  for (const Eigen::Vector3d& p : t.mesh.positions) {
    EXPECT_NEAR(Eigen::Vector2d(p.head<2>().norm() - 0.05, p.z()).norm(), 0.01, 1e-15);
  }
}

TEST(MeshGenerators, TextureCoordinatesAtTheStatedScale) {
  // Around a closed loop the tile is rounded to whole tiles: 2 pi 0.05 m / 0.01 m = 31.4 -> 31.
  const GeneratedMesh s = sphere(0.05, 64, 32, 0.01);
  EXPECT_NEAR(s.tile_used_m.x(), 2 * M_PI * 0.05 / 31, 1e-15);
  double u_max = 0, v_max = 0;
  for (const Eigen::Vector2d& uv : s.mesh.uvs) u_max = std::max(u_max, uv.x()), v_max = std::max(v_max, uv.y());
  EXPECT_DOUBLE_EQ(u_max, 31.0);
  EXPECT_DOUBLE_EQ(v_max, 16.0);  // pi 0.05 / 0.01 = 15.7 -> 16 tiles pole to pole
  // Along a cylinder's axis the tile is as given: v = z / tile.
  const GeneratedMesh c = cylinder(0.02, 0.05, 32, 5, 0.01);
  for (std::size_t i = 0; i < c.mesh.positions.size(); ++i) EXPECT_NEAR(c.mesh.uvs[i].y(), c.mesh.positions[i].z() / 0.01, 1e-12);
  // On a box face, uv is position / tile from the face's corner.
  const GeneratedMesh b = box({0.04, 0.02, 0.02}, 0.01, 0.02);
  for (std::size_t i = 0; i < b.mesh.positions.size(); ++i) {
    EXPECT_GE(b.mesh.uvs[i].minCoeff(), 0.0);
    EXPECT_LE(b.mesh.uvs[i].maxCoeff(), 2.0 + 1e-12);
  }
}

TEST(MeshGenerators, ImpossibleShapesAreRefusedNamingTheGenerator) {
  auto message = [](auto&& make) {
    try {
      make();
    } catch (const thx::Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message([] { sphere(-0.01, 16, 8, 0.01); }).find("sphere: radius"), std::string::npos);
  EXPECT_NE(message([] { sphere(0.01, 2, 8, 0.01); }).find("sphere: segments 2"), std::string::npos);
  EXPECT_NE(message([] { torus(0.01, 0.02, 16, 8, 0.01); }).find("torus: expected major radius > minor radius"),
            std::string::npos);
  EXPECT_NE(message([] { cylinder(0.01, 0.02, 16, 8, 0.0); }).find("cylinder: tile"), std::string::npos);
  EXPECT_NE(message([] { box({0.01, 0.0, 0.01}, 0.01, 0.01); }).find("box: every side"), std::string::npos);
  EXPECT_NE(message([] { box({1.0, 1.0, 1.0}, 1e-5, 0.01); }).find("cells along a side"), std::string::npos);
  EXPECT_NE(message([] { lathe({{0.0, 0.0}, {0.0, 0.01}}, 16, 0.01); }).find("lathe: every profile point lies on the axis"),
            std::string::npos);
  EXPECT_NE(message([] { lathe({{0.01, 0.0}, {-0.01, 0.01}}, 16, 0.01); }).find("lathe: profile point 1"),
            std::string::npos);
  EXPECT_NE(message([] { bowlProfile(0.01, 0.04, 0.006, 16); }).find("bowl:"), std::string::npos);
}

}  // namespace test_mesh_generators
