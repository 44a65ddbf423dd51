// A textured box as the eye sees it (issue 29): meshes/textured_box_mesh.hpp lays the texture on
// a box's faces as the physics reads it (faceTextureAt): at any point of any face the map's normal,
// carried through the mesh's interpolated frame, is the physics' relief normal there, so the box the
// eye sees is the box the contacts feel.
#include <gtest/gtest.h>

#include <cmath>

#include "base/error.hpp"
#include "clients/physics/textured_box.hpp"
#include "meshes/textured_box_mesh.hpp"
#include "tests/physics/grooved_block_scene.hpp"
#include "tests/physics/physics_fixtures.hpp"

namespace thx::phys::test::test_textured_box_mesh {
namespace {

using namespace grooved_block;

// The face's triangle holding p (on the face, within its rectangle) and its barycentric place.
std::pair<std::uint32_t, Eigen::Vector3d> triangleAt(const mesh::TexturedMesh& box, const Eigen::Vector3d& p) {
  double best = 1e9;
  std::pair<std::uint32_t, Eigen::Vector3d> found{0, Eigen::Vector3d::Zero()};
  for (std::uint32_t t = 0; t < box.triangles.size(); ++t) {
    const Eigen::Vector3d b = mesh::closestBarycentric(box, t, p);
    const auto& tri = box.triangles[t];
    const Eigen::Vector3d q = b[0] * box.positions[tri[0]] + b[1] * box.positions[tri[1]] + b[2] * box.positions[tri[2]];
    if ((q - p).norm() < best) best = (q - p).norm(), found = {t, b};
  }
  return found;
}

TEST(TexturedBoxMesh, TheMeshLaysTheTextureAsThePhysicsReadsIt) {
  const tex::TextureMap map = heightMap(128, kExtent, [](double x, double y) {
    return -kDepth * 0.5 * (1.0 + std::sin(2 * M_PI * x / kPeriod) * std::cos(2 * M_PI * y / (1.5 * kPeriod)));
  });
  FaceTexture faces;
  faces.map = &map;
  faces.tile_m = 0.013;  // not the map's extent: only the layout is compared
  const Eigen::Vector3d size(0.03, 0.02, 0.012);
  const mesh::TexturedMesh box = mesh::texturedBoxMesh(size, faces.tile_m);
  ASSERT_EQ(box.triangles.size(), 12u);
  const Eigen::Vector3d half = 0.5 * size;
  int compared = 0;
  for (int a = 0; a < 3; ++a)
    for (const double sign : {1.0, -1.0})
      for (const double s : {-0.83, -0.31, 0.07, 0.52, 0.9})
        for (const double t : {-0.77, -0.12, 0.44, 0.86}) {
          Eigen::Vector3d p;
          p[a] = sign * half[a];
          p[(a + 1) % 3] = s * half[(a + 1) % 3];
          p[(a + 2) % 3] = t * half[(a + 2) % 3];
          const FacePoint physics = faceTextureAt(faces, half, p);
          ASSERT_EQ(physics.axis, a);
          const auto [triangle, b] = triangleAt(box, p);
          const mesh::SurfaceFrame f = mesh::frameAt(box, triangle, b, mesh::FrameMode::Interpolated);
          EXPECT_TRUE(f.normal.isApprox(sign * Eigen::Vector3d::Unit(a), 1e-12)) << f.normal.transpose();
          const tex::Sample sample = tex::sample(map, {f.uv.x(), f.uv.y()}, faces.sampling);
          const Eigen::Vector3d seen =
              (double(sample.normal.x()) * f.tangent + double(sample.normal.y()) * f.bitangent +
               double(sample.normal.z()) * f.normal)
                  .normalized();
          EXPECT_LT((seen - physics.normal_object).norm(), 1e-6)
              << "face " << a << (sign > 0 ? "+" : "-") << " at " << p.transpose() << ": " << seen.transpose()
              << " / " << physics.normal_object.transpose();
          ++compared;
        }
  EXPECT_EQ(compared, 120);
}

TEST(TexturedBoxMesh, BadSizesAreRefused) {
  EXPECT_THROW(mesh::texturedBoxMesh({0.01, 0.0, 0.01}, 0.01), thx::Error);
  EXPECT_THROW(mesh::texturedBoxMesh({0.01, 0.01, 0.01}, -1.0), thx::Error);
  EXPECT_THROW(mesh::texturedBoxMesh({0.01, NAN, 0.01}, 0.01), thx::Error);
}

}  // namespace
}  // namespace thx::phys::test::test_textured_box_mesh
