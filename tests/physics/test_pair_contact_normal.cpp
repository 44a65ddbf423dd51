// Which normal a contact between a relief plane and a textured box takes
// (clients/physics/pair_contact_normal.hpp): where a crest of one presses on the other's flat
// wall or face, the wall's; where both bend gently, or both have a crease, the rasteriser's mean
// of the two.
#include <gtest/gtest.h>

#include <cmath>

#include "clients/physics/pair_contact_normal.hpp"
#include "tests/physics/grooved_block_scene.hpp"

namespace thx::phys::test::test_pair_contact_normal {
namespace {

using namespace grooved_block;

constexpr int kTexels = 128;  // 0.3125 mm over 4 cm

// The contact the rasteriser would make at the plane's texel under (x, y), its normal set to a
// marker that no rule below produces.
ReliefCandidate contactAt(const tex::TexturedSurface& surface, double x, double y) {
  ReliefCandidate c;
  surface.texelContaining(x, y, c.i, c.j);
  c.p_surface = surface.texelPoint(c.i, c.j).q_local;
  c.n_local = Eigen::Vector3d(0.1, 0.2, 1.0).normalized();
  return c;
}

Eigen::Vector3d chosenNormal(const tex::TexturedSurface& plane, const tex::TextureMap& box_map, const Eigen::Isometry3d& box_pose,
                             double x, double y) {
  FaceTexture faces;
  faces.map = &box_map;
  faces.tile_m = kExtent;
  const Underside box = Underside::box(box_pose, kHalf);
  std::array<ReliefCandidate, 1> c{contactAt(plane, x, y)};
  smootherSurfaceNormals(plane, nullptr, TexturedObjectSurface(box, faces), c);
  return c[0].n_local;
}

TEST(PairContactNormal, ARidgeOfThePlaneUnderAFlatFaceTakesTheFacesNormal) {
  const SurfaceHolder plane = holdSurface(heightMap(kTexels, kExtent, vGrooves), kExtent, true);
  const tex::TextureMap flat = flatRelief(kTexels);
  // The box tilted 3° about y, its face resting on the ridge at x = 0.
  Eigen::Isometry3d pose = at(0.0, 0.0, kHalf.z());
  pose.linear() = Eigen::AngleAxisd(deg(3.0), Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Vector3d face_up = pose.linear().col(2);
  const Eigen::Vector3d n = chosenNormal(plane.surface, flat, pose, 0.0, 0.0);
  EXPECT_LT((n - face_up).norm(), 1e-9) << n.transpose() << " / " << face_up.transpose();
}

TEST(PairContactNormal, ARidgeOfTheBoxOnAWallOfThePlaneTakesTheWallsNormal) {
  const SurfaceHolder plane = holdSurface(heightMap(kTexels, kExtent, vGrooves), kExtent, true);
  const tex::TextureMap grooved = heightMap(kTexels, kExtent, vGrooves);
  // The box's ridge (its face's u = 0) over the plane's wall half way down from the ridge at
  // x = 0 to the floor at x = P/2, whose normal leans 26.6° towards +x.
  const double x = 0.25 * kPeriod;
  const Eigen::Vector3d n = chosenNormal(plane.surface, grooved, at(x, 0.0, kHalf.z() - 0.5 * kDepth), x, 0.0);
  const double wall = std::atan(2.0 * kDepth / kPeriod);
  EXPECT_NEAR(n.x(), std::sin(wall), 2e-3) << n.transpose();
  EXPECT_NEAR(n.z(), std::cos(wall), 2e-3) << n.transpose();
}

TEST(PairContactNormal, AWallOnAWallAndGentleBumpsKeepTheMean) {
  const SurfaceHolder plane = holdSurface(heightMap(kTexels, kExtent, vGrooves), kExtent, true);
  const tex::TextureMap grooved = heightMap(kTexels, kExtent, vGrooves);
  const Eigen::Vector3d marker = contactAt(plane.surface, 0.0, 0.0).n_local;
  // The block's ridges in the plane's floors: a wall of each on a wall of the other.
  const double x = 0.25 * kPeriod;
  EXPECT_EQ(chosenNormal(plane.surface, grooved, at(0.5 * kPeriod, 0.0, kHalf.z() - kDepth), x, 0.0), marker);
  // Bumps 4 mm apart, 0.1 mm high under a flat face: their slope changes by far less than
  // kCreaseSlopeJump over a texel.
  const SurfaceHolder bumps = holdSurface(
      heightMap(kTexels, kExtent, [](double px, double) { return 5e-5 * (std::cos(2.0 * kPi * px / kPeriod) - 1.0); }), kExtent,
      true);
  EXPECT_EQ(chosenNormal(bumps.surface, flatRelief(kTexels), at(0.0, 0.0, kHalf.z()), 0.0, 0.0), marker);
}

TEST(PairContactNormal, ARidgeOnARidgeKeepsTheMean) {
  const SurfaceHolder plane = holdSurface(heightMap(kTexels, kExtent, vGrooves), kExtent, true);
  const tex::TextureMap grooved = heightMap(kTexels, kExtent, vGrooves);
  const Eigen::Vector3d marker = contactAt(plane.surface, 0.0, 0.0).n_local;
  // The box's ridge (its face's u = 0) on the plane's ridge at x = 0: neither is the face.
  EXPECT_EQ(chosenNormal(plane.surface, grooved, at(0.0, 0.0, kHalf.z()), 0.0, 0.0), marker);
}

TEST(PairContactNormal, AtTheFootprintsRimTheBoxIsMeasuredOneTexelIn) {
  const SurfaceHolder plane = holdSurface(heightMap(kTexels, kExtent, vGrooves), kExtent, true);
  const tex::TextureMap flat = flatRelief(kTexels);
  // The ridge at x = 2 P = 8 mm under the box's edge there: the last texel centre under the box
  // (7.97 mm) has no box beyond it, the plane's ridge lies between it and the next.
  const Eigen::Isometry3d pose = at(2.0 * kPeriod - kHalf.x(), 0.0, kHalf.z());
  const double x = 2.0 * kPeriod - 0.1 * kExtent / kTexels;
  EXPECT_EQ(chosenNormal(plane.surface, flat, pose, x, 0.0), Eigen::Vector3d::UnitZ());
  // The same along y, the ridge square to the box's edge at y = 10 mm.
  const double edge_y = kHalf.y() - 0.5 * kExtent / kTexels;
  EXPECT_EQ(chosenNormal(plane.surface, flat, at(0.0, 0.0, kHalf.z()), 0.0, edge_y), Eigen::Vector3d::UnitZ());
}

}  // namespace
}  // namespace thx::phys::test::test_pair_contact_normal
