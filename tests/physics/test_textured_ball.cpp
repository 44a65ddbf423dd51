// A ball with a bump map (issue 29, "a sphere with a bump map"; clients/physics/textured_ball.hpp):
// its texture read through the cube-sphere layout (meshes/textured_ball_mesh.hpp), recessed along
// the radius, with the recessed surface's normal; on a relief plane both textures shape the
// contact, the point of contact on the recessed surface.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "clients/physics/pair_contact_normal.hpp"
#include "clients/physics/relief_raster.hpp"
#include "tests/physics/textured_ball_scene.hpp"

namespace thx::phys::test::test_textured_ball {
namespace {

using namespace textured_ball;

// The recessed surface at direction w: (r - d(w)) w.
Eigen::Vector3d recessedPoint(const FaceTexture& texture, const Eigen::Vector3d& w) {
  return (kRadius - ballTextureAt(texture, kRadius, w).recess_m) * w.normalized();
}

TEST(BallTexture, TheNormalIsTheRecessedSurfacesOwn) {
  const tex::TextureMap map = bumpMap(3e-4);  // slopes up to 0.24
  const FaceTexture texture = ballTexture(map);
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss;
  int checked = 0;
  double worst = 0.0;
  while (checked < 200) {
    const Eigen::Vector3d w = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    // Away from the faces' edges, where the finite differences below would straddle two charts.
    Eigen::Vector3d sorted = w.cwiseAbs();
    std::sort(sorted.data(), sorted.data() + 3);
    if (sorted[2] < 1.02 * sorted[1]) continue;
    ++checked;
    // Two tangent directions and the surface's derivatives along them, 0.1 mm steps (1.6 texels).
    const Eigen::Vector3d t1 = w.unitOrthogonal(), t2 = w.cross(t1);
    const double h = 1e-4 / kRadius;
    const Eigen::Vector3d d1 = recessedPoint(texture, w + h * t1) - recessedPoint(texture, w - h * t1);
    const Eigen::Vector3d d2 = recessedPoint(texture, w + h * t2) - recessedPoint(texture, w - h * t2);
    const Eigen::Vector3d expected = d1.cross(d2).normalized();
    const Eigen::Vector3d n = ballTextureAt(texture, kRadius, w).normal_object;
    worst = std::max(worst, std::acos(std::clamp(n.dot(expected), -1.0, 1.0)));
  }
  // The map's normals against its bilinear depth's differences: 1.6 texels apart, on bumps whose
  // slope turns by 0.06 per texel.
  EXPECT_LT(worst, 0.012) << worst;
}

TEST(BallTexture, ASymmetricTextureContinuesAcrossEveryFacesEdge) {
  const tex::TextureMap map = bumpMap(3e-4);
  const FaceTexture texture = ballTexture(map);
  double worst = 0.0;
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    for (const double sa : {-1.0, 1.0})
      for (const double sb : {-1.0, 1.0})
        for (int k = -20; k <= 20; ++k) {
          // Either side of the edge between the faces of a and of b, at 2 µm.
          Eigen::Vector3d on_a = Eigen::Vector3d::Zero(), on_b = Eigen::Vector3d::Zero();
          const double along = std::tan(0.25 * kPi * double(k) / 21.0);
          on_a[a] = sa * (1.0 + 2e-4), on_a[b] = sb, on_a[c] = along;
          on_b[a] = sa, on_b[b] = sb * (1.0 + 2e-4), on_b[c] = along;
          const FacePoint fa = ballTextureAt(texture, kRadius, on_a), fb = ballTextureAt(texture, kRadius, on_b);
          ASSERT_EQ(fa.axis, a);
          ASSERT_EQ(fb.axis, b);
          worst = std::max(worst, std::fabs(fa.recess_m - fb.recess_m));
        }
  }
  // The bumps' slope over 2 µm either side, and the depth codes' rounding.
  EXPECT_LT(worst, 1e-6) << worst;
}

TEST(BallTexture, TheTextureLiesAtItsStatedScaleAlongTheFacesGreatCircles) {
  const tex::TextureMap map = bumpMap(3e-4);
  const FaceTexture texture = ballTexture(map);
  // The face's centre is the tile's corner, a valley between bumps; half a bump period along the
  // surface from it in u and in v (along the great circles through the centre: u = r atan(x/|z|)
  // on the -z face), a bump's tip.
  const double valley = ballTextureAt(texture, kRadius, {0.0, 0.0, -1.0}).recess_m;
  const double t = std::tan(0.5 * (kTile / 4.0) / kRadius);
  const double tip = ballTextureAt(texture, kRadius, {t, t, -1.0}).recess_m;
  EXPECT_NEAR(valley, 3e-4, 2e-6);
  EXPECT_NEAR(tip, 0.0, 2e-6);
}

// The raster reads a ball's texture for its depth alone, and its normal at the points kept
// (withNormals): the same candidates, depths and normals as reading both everywhere, to the
// bit, over many poses of a bumpy ball on a bumpy relief.
TEST(BallTexture, ItsDepthAloneUnderEveryTexelAndItsNormalWhereKeptAreTheFullReadsToTheBit) {
  const tex::TextureMap ball_map = bumpMap(3e-4);
  const FaceTexture texture = ballTexture(ball_map);
  const SurfaceHolder plane = holdSurface(heightMap(256, 0.04, [](double x, double y) { return bumps(x, y, 4e-4, 0.002); }),
                                          0.04, true);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::size_t compared = 0;
  for (int pose = 0; pose < 40; ++pose) {
    Eigen::Isometry3d at = Eigen::Isometry3d::Identity();
    at.linear() = Eigen::Quaterniond(Eigen::Vector4d(unit(rng), unit(rng), unit(rng), unit(rng)).normalized()).toRotationMatrix();
    at.translation() = Eigen::Vector3d(0.003 * unit(rng), 0.003 * unit(rng), kRadius - 3e-4 + 2e-4 * unit(rng));
    const Underside ball = Underside::sphere(at, kRadius);
    std::vector<ReliefCandidate> full, depth_only;
    rasterizeRelief(plane.surface, ball, 5e-4, full, &texture);
    rasterizeRelief(plane.surface, ball, 5e-4, depth_only, &texture, nullptr, false);
    const TexturedObjectSurface surface(ball, texture);
    ASSERT_EQ(full.size(), depth_only.size()) << pose;
    for (std::size_t k = 0; k < full.size(); ++k) {
      ReliefCandidate c = depth_only[k];
      EXPECT_EQ(c.depth, full[k].depth);
      EXPECT_EQ(c.p_surface, full[k].p_surface);
      withNormals(plane.surface, nullptr, &surface, c);
      EXPECT_EQ(c.n_local, full[k].n_local) << pose << " " << k;
    }
    compared += full.size();
  }
  EXPECT_GT(compared, 1000u);
}

TEST(TexturedBall, AUniformlyRecessedBallRestsAndRollsOnItsRecessedSurface) {
  const double depth = 5e-4;
  const tex::TextureMap map = uniformRecess(depth);
  const FaceTexture texture = ballTexture(map);
  {
    PhysicsWorld world;
    const SurfaceHolder plane = holdSurface(flatRelief(256), 0.04, true);
    world.addReliefPlane(plane.surface, {0.5, 0.0, 0.0});
    btRigidBody& ball = world.addTexturedSphere(kRadius, kMass, at(0.0, 0.0, kRadius - depth + 1e-4), {0.5, 0.0, 0.0}, texture);
    for (int k = 0; k < 500; ++k) world.step(kDt);
    EXPECT_NEAR(positionOf(ball).z(), kRadius - depth, 2e-6);
    EXPECT_LT(velocityOf(ball).norm(), 1e-4);
  }
  // Rolling without slipping on a radius rho = r - depth with the coarse ball's inertia
  // (2/5 m r^2): a = g sin(slope) / (1 + 2 r^2 / (5 rho^2)), 3 % below a ball of radius r's 5/7 g
  // sin(slope). The push acts on the recessed surface, not where the smooth ball would touch.
  const double slope = 5.0, seconds = 0.3;
  const double rho = kRadius - depth;
  const double expected = kG * std::sin(deg(slope)) / (1.0 + 0.4 * kRadius * kRadius / (rho * rho)) * seconds;
  const double smooth = 5.0 / 7.0 * kG * std::sin(deg(slope)) * seconds;
  EXPECT_NEAR(rollingSpeed(&texture, slope, seconds, kRadius - depth), expected, 0.002 * expected);
  EXPECT_NEAR(rollingSpeed(nullptr, slope, seconds, kRadius), smooth, 0.002 * smooth);
}

// The normal flatterReliefNormals gives a contact at the plane's texel under (x, y), set to a marker
// no rule produces, under the bumpy ball centred over the origin.
Eigen::Vector3d flatterNormal(const tex::TextureMap& plane_map, double x, double y) {
  const tex::TextureMap map = bumpMap(3e-4);
  const FaceTexture texture = ballTexture(map);
  const SurfaceHolder plane = holdSurface(plane_map, 0.04, true);
  const Underside ball = Underside::sphere(at(0.0, 0.0, kRadius), kRadius);
  std::array<ReliefCandidate, 1> c{};
  plane.surface.texelContaining(x, y, c[0].i, c[0].j);
  c[0].p_surface = plane.surface.texelPoint(c[0].i, c[0].j).q_local;
  c[0].n_local = Eigen::Vector3d(0.1, 0.2, 1.0).normalized();
  flatterReliefNormals(plane.surface, nullptr, TexturedObjectSurface(ball, texture), c);
  return c[0].n_local;
}

TEST(TexturedBall, OnAFlatStretchOfTheReliefAContactTakesTheReliefsNormal) {
  // A flat relief under the ball: the relief's normal.
  EXPECT_LT((flatterNormal(flatRelief(256), 0.0005, 0.0003) - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  // A bump's tip of the plane (0.4 mm high, 2 mm apart: its curvature 20 times the ball's sphere's)
  // under the ball: the contact keeps its normal.
  const Eigen::Vector3d kept = flatterNormal(bumpyPlane(256), 0.001, 0.001);
  EXPECT_LT((kept - Eigen::Vector3d(0.1, 0.2, 1.0).normalized()).norm(), 1e-12) << kept.transpose();
}

// A bumpy ball let down onto `plane_map` rests where its lowest bump tips touch the plane's relief:
// the gap found over the ball's own directions is zero, within `tolerance`; after `seconds` it
// moves slower than `speed`, the fastest over the last 0.5 s; lower than a smooth ball by less than
// the bumps' height.
void expectRestsTouching(const tex::TextureMap& plane_map, const char* what, double tolerance, double seconds,
                         double speed) {
  const Settled s = settleBumpyBall(plane_map, seconds);
  EXPECT_LT(s.fastest, speed) << what;
  EXPECT_NEAR(s.gap, 0.0, tolerance) << what << ": centre at " << s.centre.transpose();
  EXPECT_LT(s.height, kRadius) << what;
  EXPECT_GT(s.height, kRadius - 3e-4 - 1e-3) << what;
}

TEST(TexturedBall, ABumpyBallRestsOnItsBumpsOnAFlatRelief) {
  // Measured: 0.1 µm over the plane, at rest: on flat ground it meets it by its own lowest points
  // (ball_on_flat_ground.hpp). Read at the plane's texels it rested 3 µm into the plane; with the
  // rasteriser's mean normals it crept at 6 µm/s and from 3.9 s cycled every six steps at up to
  // 0.31 mm/s (flatterReliefNormals).
  expectRestsTouching(flatRelief(256), "flat", 5e-6, 4.0, 1e-4);
}

TEST(TexturedBall, ABumpyBallOnABumpyPlaneRestsWhereBothReliefsTouch) {
  // Tip on tip. The plane's relief is read bilinearly between its 0.16 mm texels, which cuts up
  // to 12 µm off its tips (measured: 11 µm into them; +1.5 µm at 512 texels). It does not fall
  // silent: from 2.5 s it creeps at about 25 µm/s, its speed jittering up to 0.9 mm/s
  // (docs/physics.md, Known gaps).
  expectRestsTouching(bumpyPlane(256), "bumpy", 1.5e-5, 3.0, 1.5e-3);
}

TEST(TexturedBall, ABumpyBallRollingOverAFlatReliefGainsNoEnergy) {
  const tex::TextureMap map = bumpMap(3e-4);
  const FaceTexture texture = ballTexture(map);
  PhysicsWorld world;
  const SurfaceHolder plane = holdSurface(flatRelief(256), 0.04, true);
  world.addReliefPlane(plane.surface, {0.5, 0.0, 0.0});
  btRigidBody& ball = world.addTexturedSphere(kRadius, kMass, at(0.0, 0.0, kRadius), {0.5, 0.0, 0.0}, texture);
  setRolling(ball, 0.1, kRadius);
  const double inertia = 0.4 * kMass * kRadius * kRadius;
  auto energy = [&] {
    const Eigen::Vector3d v = velocityOf(ball), w = toEigen(ball.getAngularVelocity());
    return 0.5 * kMass * v.squaredNorm() + 0.5 * inertia * w.squaredNorm() + kMass * kG * positionOf(ball).z();
  };
  const double start = energy();
  double highest = start;
  for (int k = 0; k < 1000; ++k) {
    world.step(kDt);
    highest = std::max(highest, energy());
  }
  const double kinetic = 0.7 * kMass * 0.1 * 0.1;
  EXPECT_LT(highest - start, 0.02 * kinetic) << (highest - start) / kinetic;
  EXPECT_GT(velocityOf(ball).x(), 0.0);  // still rolling the way it was sent
}

}  // namespace
}  // namespace thx::phys::test::test_textured_ball
