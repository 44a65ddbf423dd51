// A textured ball as the eye sees it (issue 29): meshes/textured_ball_mesh.hpp lays the texture on
// the ball as the physics reads it (ballChartAt, through ballTextureAt): the same uv at every
// vertex, tangents along the chart's u, normals along the radius; bad sizes refused.
#include <gtest/gtest.h>

#include <cmath>

#include "base/error.hpp"
#include "clients/physics/textured_ball.hpp"
#include "meshes/textured_ball_mesh.hpp"
#include "tests/physics/textured_ball_scene.hpp"

namespace thx::phys::test::test_textured_ball_mesh {
namespace {

using textured_ball::kRadius;

// Whether a direction lies strictly inside one face's chart (not on an edge two faces share).
bool insideAFace(const Eigen::Vector3d& p) {
  Eigen::Vector3d a = p.cwiseAbs();
  std::sort(a.data(), a.data() + 3);
  return a[2] > a[1] * (1.0 + 1e-9);
}

TEST(TexturedBallMesh, EveryVertexCarriesThePhysicsUvAndAFrameAlongItsChart) {
  const double tile = mesh::ballFaceArc(kRadius);
  const mesh::TexturedMesh ball = mesh::texturedBallMesh(kRadius, tile, 24);
  ASSERT_EQ(ball.triangles.size(), 6u * 2u * 24u * 24u);
  ASSERT_TRUE(ball.hasFrames());
  double worst_uv = 0.0, worst_normal = 0.0, worst_tangent = 0.0;
  int inside = 0;
  for (std::size_t v = 0; v < ball.positions.size(); ++v) {
    const Eigen::Vector3d& p = ball.positions[v];
    EXPECT_NEAR(p.norm(), kRadius, 1e-12);
    worst_normal = std::max(worst_normal, std::acos(std::min(1.0, ball.normals[v].dot(p.normalized()))));
    if (!insideAFace(p)) continue;
    ++inside;
    const mesh::BallChartPoint chart = mesh::ballChartAt(p, kRadius);
    worst_uv = std::max(worst_uv, (ball.uvs[v] * tile - chart.uv_m).norm());
    // The mesh's tangent is the direction the point moves in as u grows (v held): e_(a+1) laid
    // onto the tangent plane. (Not the gradient of u, chart.du, where the chart shears.)
    const Eigen::Vector3d n = p.normalized(), e = Eigen::Vector3d::Unit((chart.axis + 1) % 3);
    const Eigen::Vector3d along_u = (e - e.dot(n) * n).normalized();
    worst_tangent = std::max(worst_tangent, std::acos(std::min(1.0, ball.tangents[v].dot(along_u))));
    // Mirrored on the negative faces, as the box's are.
    EXPECT_EQ(ball.handedness[v], float(chart.sign)) << p.transpose();
  }
  EXPECT_GT(inside, 6 * 23 * 23 - 1);
  EXPECT_LT(worst_uv, 1e-12);
  // The frames are the faces' means around each vertex: within a cell's turn of the exact ones.
  EXPECT_LT(worst_normal, 0.01) << worst_normal;
  EXPECT_LT(worst_tangent, 0.02) << worst_tangent;
}

// The map's normal carried through the mesh's interpolated frame (what the shaders do) against the
// physics' (ballTextureAt: the recessed surface's own normal, through the chart's gradients). The
// mesh's frame is orthonormal, the chart's gradients are not where the chart shears (towards the
// cube's corners, 30 degrees at them): there the two part, measured up to 0.084 rad on bumps of
// slope up to 0.24; along the great circles through a face's centre (one coordinate zero) the
// chart is orthogonal and they agree (measured 0.0004 rad: the mesh's frames are its faces' means).
TEST(TexturedBallMesh, TheShadedNormalIsThePhysicsNormalWhereTheChartIsOrthogonal) {
  const tex::TextureMap map = textured_ball::bumpMap(3e-4);  // slopes up to 0.24
  const FaceTexture texture = textured_ball::ballTexture(map);
  const mesh::TexturedMesh ball = mesh::texturedBallMesh(kRadius, texture.tile_m, 24);
  double on_axes = 0.0, anywhere = 0.0;
  for (int a = 0; a < 3; ++a)
    for (const double sign : {1.0, -1.0})
      for (const double s : {-0.9, -0.55, 0.0, 0.31, 0.8})
        for (const double t : {-0.85, 0.0, 0.42, 0.93}) {
          Eigen::Vector3d w = Eigen::Vector3d::Zero();
          w[a] = sign, w[(a + 1) % 3] = std::tan(0.25 * kPi * s), w[(a + 2) % 3] = std::tan(0.25 * kPi * t);
          const Eigen::Vector3d p = kRadius * w.normalized();
          double best = 1e9;
          std::uint32_t triangle = 0;
          Eigen::Vector3d b = Eigen::Vector3d::Zero();
          for (std::uint32_t k = 0; k < ball.triangles.size(); ++k) {
            const Eigen::Vector3d bk = mesh::closestBarycentric(ball, k, p);
            const auto& tri = ball.triangles[k];
            const Eigen::Vector3d q = bk[0] * ball.positions[tri[0]] + bk[1] * ball.positions[tri[1]] + bk[2] * ball.positions[tri[2]];
            if ((q - p).norm() < best) best = (q - p).norm(), triangle = k, b = bk;
          }
          const mesh::SurfaceFrame f = mesh::frameAt(ball, triangle, b, mesh::FrameMode::Interpolated);
          // Sampled where the physics samples it (the flat triangle's uv differs from the sphere's).
          const mesh::BallChartPoint chart = mesh::ballChartAt(p, kRadius);
          const tex::Sample sample = tex::sample(map, {chart.uv_m.x() / texture.tile_m, chart.uv_m.y() / texture.tile_m}, texture.sampling);
          const Eigen::Vector3d seen = (double(sample.normal.x()) * f.tangent + double(sample.normal.y()) * f.bitangent +
                                        double(sample.normal.z()) * f.normal)
                                           .normalized();
          const double angle = std::acos(std::clamp(seen.dot(ballTextureAt(texture, kRadius, p).normal_object), -1.0, 1.0));
          anywhere = std::max(anywhere, angle);
          if (s == 0.0 || t == 0.0) on_axes = std::max(on_axes, angle);
        }
  EXPECT_LT(on_axes, 0.002);
  EXPECT_LT(anywhere, 0.1);
}

TEST(TexturedBallMesh, TheChartsGradientsAreTheFacesDirectionsAtTheirCentres) {
  for (int a = 0; a < 3; ++a)
    for (const double sign : {-1.0, 1.0}) {
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      centre[a] = sign;
      const mesh::BallChartPoint chart = mesh::ballChartAt(centre, kRadius);
      EXPECT_EQ(chart.axis, a);
      EXPECT_EQ(chart.sign, sign);
      EXPECT_LT(chart.uv_m.norm(), 1e-15);
      EXPECT_LT((chart.du - Eigen::Vector3d::Unit((a + 1) % 3)).norm(), 1e-15);
      EXPECT_LT((chart.dv - Eigen::Vector3d::Unit((a + 2) % 3)).norm(), 1e-15);
    }
  // Along a great circle through a face's centre u is the arc length: r pi/4 at the edge.
  EXPECT_NEAR(mesh::ballChartAt({0.0, 1.0, 1.0 + 1e-12}, kRadius).uv_m.y(), 0.25 * M_PI * kRadius, 1e-12);
}

// The chart's angles come from its own arctangent (a knot table and a short series, cheaper than
// libm's atan2 at every texel under a ball): within a few ulp of libm's over whole faces, on the
// knots, between them, at the faces' centres and at their edges.
TEST(TexturedBallMesh, TheChartsAnglesAreLibmsToAFewUlp) {
  const double quarter_arc = 0.25 * M_PI;  // the angle at a face's edge
  double worst = 0.0;
  int points = 0;
  for (int a = 0; a < 3; ++a)
    for (const double sign : {-1.0, 1.0})
      for (int i = -400; i <= 400; ++i)
        for (int j = -400; j <= 400; j += 7) {
          Eigen::Vector3d w = Eigen::Vector3d::Zero();
          // i / 400 lands on every other knot (k / 32 for even k); j steps between them.
          w[a] = sign;
          w[(a + 1) % 3] = double(i) / 400.0;
          w[(a + 2) % 3] = double(j) / 400.0 + (j % 2 ? 1e-7 : 0.0);
          if (std::fabs(w[(a + 2) % 3]) > 1.0) continue;
          const Eigen::Vector3d unit = w.normalized();
          const mesh::BallChartPoint chart = mesh::ballChartUvAtUnit(unit, 1.0);
          const double wa = std::fabs(unit[chart.axis]);
          const Eigen::Vector2d libm(std::atan2(unit[(chart.axis + 1) % 3], wa),
                                     std::atan2(unit[(chart.axis + 2) % 3], wa));
          worst = std::max(worst, (chart.uv_m - libm).cwiseAbs().maxCoeff());
          ++points;
        }
  EXPECT_GT(points, 6 * 801 * 100);
  // A few ulp of angles up to pi/4 (one ulp there is 1.1e-16).
  EXPECT_LT(worst, 5e-16) << worst;
  EXPECT_EQ(mesh::ballChartUvAtUnit(Eigen::Vector3d(1.0, 1.0, 0.0).normalized(), 1.0).uv_m.x(),
            std::atan2(1.0, 1.0));
  EXPECT_NEAR(mesh::ballChartUvAtUnit(Eigen::Vector3d(1.0, -1.0, 1.0).normalized(), 1.0).uv_m.y(), quarter_arc,
              2e-16);
}

TEST(TexturedBallMesh, ABadRadiusTileOrCellCountIsRefused) {
  EXPECT_THROW(mesh::texturedBallMesh(0.0, 0.01), Error);
  EXPECT_THROW(mesh::texturedBallMesh(0.01, -1.0), Error);
  EXPECT_THROW(mesh::texturedBallMesh(0.01, std::nan("")), Error);
  EXPECT_THROW(mesh::texturedBallMesh(0.01, 0.01, 0), Error);
}

}  // namespace
}  // namespace thx::phys::test::test_textured_ball_mesh
