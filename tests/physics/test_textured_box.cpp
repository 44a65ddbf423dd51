// A box whose faces carry a relief, on a relief plane (issue 29, "Textured objects";
// clients/physics/textured_box.hpp): V-grooves under a block grooved the same way and set half a
// period over, so its ridges sit in the plane's grooves. Both textures shape the contact: the
// block slides along the grooves and not across them, where a plain block of the same size rides
// the ridges' tops either way.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>

#include "clients/physics/textured_box.hpp"
#include "clients/physics/textured_box_rows.hpp"
#include "clients/physics/textured_object_surface.hpp"
#include "tests/physics/grooved_block_scene.hpp"

namespace thx::phys::test::test_textured_box {
namespace {

using namespace grooved_block;

TEST(TexturedBox, AGroovedBlockSitsInTheGroovesOfAGroovedPlane) {
  Scene textured(true, false), plain(false, false);
  // The textured block's face sinks to the grooves' floor (its ridges fit the plane's floors),
  // the plain one rests on the ridges' tops.
  // Within the bilinear rounding of the two V's creases (0.31 mm texels: up to half a texel of a
  // 0.5 slope each, 78 µm).
  EXPECT_NEAR(positionOf(*textured.block).z(), kHalf.z() - kDepth, 1.6e-4);
  EXPECT_NEAR(positionOf(*plain.block).z(), kHalf.z(), 1.6e-4);
  EXPECT_NEAR(positionOf(*textured.block).x(), 0.5 * kPeriod, 1.6e-4);
  const Eigen::Vector3d up = toEigen(textured.block->getWorldTransform().getBasis().getColumn(2));
  EXPECT_GT(up.z(), std::cos(deg(0.5)));
}

TEST(TexturedBox, AGroovedBlockSlidesAlongTheGroovesAndNotAcrossThem) {
  // Half the weight, sideways: more than friction (0.3) alone resists, less than a 26.6° wall
  // with it (tan(26.6° + 16.7°) = 0.94).
  ASSERT_LT(alongForce(), 0.5);
  ASSERT_GT(acrossForce(), 0.5);
  Scene along(true, false), across(true, false), plain_across(false, false);
  const Eigen::Vector3d a = along.push({0.0, 0.5, 0.0}, 0.2);
  const Eigen::Vector3d c = across.push({0.5, 0.0, 0.0}, 0.2);
  const Eigen::Vector3d p = plain_across.push({0.5, 0.0, 0.0}, 0.2);
  // Along: (0.5 - 0.3) g for 0.2 s is 39 mm.
  EXPECT_NEAR(a.y(), 0.5 * (0.5 - 0.3) * kG * 0.04, 0.1 * 0.0392) << a.transpose();
  EXPECT_LT(std::fabs(a.x()), 3e-4) << a.transpose();
  // Across it stays in its grooves (it settles onto the walls by a fraction of a millimetre; see
  // docs/physics.md "Textured objects" for the force that moves it on).
  EXPECT_LT(c.norm(), 0.25 * kPeriod) << c.transpose();
  EXPECT_GT(p.x(), 0.5 * 0.5 * (0.5 - 0.3) * kG * 0.04) << p.transpose();
  // Twice the wall's share: it climbs out across the grooves.
  Scene hard(true, false);
  EXPECT_GT(hard.push({1.3, 0.0, 0.0}, 0.2).x(), kPeriod);
}

TEST(TexturedBox, AForceRaisedSlowlyToMostOfTheWedgesHoldsTheBlockInItsGrooves) {
  // Raised over 0.5 s to 0.84 of its weight and held 0.3 s, as bench_textured_pair measures it:
  // the block settles onto the walls and stays there (0.48 mm). Its walls carry the load with
  // their own normal only where a ridge pressing on the other body's wall takes the wall's
  // (pair_contact_normal.hpp): with the mean of the two normals it climbed out from 0.79 (at 0.84:
  // 28 mm).
  Scene across(true, false, 64);
  const Eigen::Vector3d moved = across.push({0.84, 0.0, 0.0}, 0.3, 0.5);
  EXPECT_LT(moved.x(), 1e-3) << moved.transpose();
  EXPECT_LT(moved.z(), 0.5 * kDepth) << moved.transpose();
}

// The same on the grooves laid on a flat slab mesh's top, met on its relief chart (bench_textured_pair's
// slab columns: the plane's forces within 0.016); and pushed well past the wedge it climbs out.
TEST(TexturedBox, OnASlabMeshTheWedgeHoldsAsOnThePlane) {
  Scene held(true, false, 64, {}, BlockGround::SlabMesh);
  const Eigen::Vector3d moved = held.push({0.84, 0.0, 0.0}, 0.3, 0.5);
  EXPECT_LT(moved.x(), 1e-3) << moved.transpose();
  EXPECT_LT(moved.z(), 0.5 * kDepth) << moved.transpose();
  Scene pushed(true, false, 64, {}, BlockGround::SlabMesh);
  EXPECT_GT(pushed.push({1.3, 0.0, 0.0}, 0.2).x(), kPeriod);
}

TEST(TexturedBox, EitherOrderOfThePairGivesTheSameMotion) {
  Scene block_first(true, true), plane_first(true, false);
  const Eigen::Vector3d a = block_first.push({0.5, 0.5, 0.0}, 0.2);
  const Eigen::Vector3d b = plane_first.push({0.5, 0.5, 0.0}, 0.2);
  EXPECT_LT((a - b).norm(), 1e-9) << a.transpose() << " / " << b.transpose();
  EXPECT_GT(a.y(), 0.01);
}

TEST(TexturedBox, TheFaceTextureIsReadOnTheFaceAPointLiesOn) {
  const tex::TextureMap map = heightMap(128, kExtent, vGrooves);
  FaceTexture faces;
  faces.map = &map;
  faces.tile_m = kExtent;
  // On the bottom face (-z): u along x, v along y; a floor of the grooves at x = P/2 lies 1 mm in.
  FacePoint f = faceTextureAt(faces, kHalf, {0.5 * kPeriod, 0.003, -kHalf.z()});
  EXPECT_EQ(f.axis, 2);
  EXPECT_EQ(f.sign, -1.0);
  EXPECT_NEAR(f.recess_m, kDepth, 8e-5);  // the crease's bilinear rounding
  // On a wall rising towards +x the relief's outward normal leans to +x, down, out of the box.
  f = faceTextureAt(faces, kHalf, {0.25 * kPeriod, 0.003, -kHalf.z()});
  EXPECT_NEAR(f.recess_m, 0.5 * kDepth, 2e-5);
  EXPECT_NEAR(f.normal_object.x(), std::sin(std::atan(2 * kDepth / kPeriod)), 1e-3) << f.normal_object.transpose();
  EXPECT_LT(f.normal_object.z(), -0.8);
  // On the +x side face: u along y, v along z, its outward normal +x.
  f = faceTextureAt(faces, kHalf, {kHalf.x(), 0.0, 0.001});
  EXPECT_EQ(f.axis, 0);
  EXPECT_EQ(f.sign, 1.0);
  EXPECT_GT(f.normal_object.x(), 0.8);
  // Just above the bottom's edge on that side, seen from a plane below (a slightly tilted box's
  // vertical line enters here): the bottom's texture, whose grooves cut through the edge.
  f = faceTextureAt(faces, kHalf, {kHalf.x(), 0.003, -kHalf.z() + 1e-5}, {0.0, 0.0, -1.0});
  EXPECT_EQ(f.axis, 2);
  EXPECT_EQ(f.sign, -1.0);
  EXPECT_NEAR(f.recess_m, kDepth, 1e-4);  // a floor half way between two texel centres
  // On the bottom's edge itself, the face turned towards the plane.
  f = faceTextureAt(faces, kHalf, {kHalf.x(), 0.003, -kHalf.z()}, {0.0, 0.0, -1.0});
  EXPECT_EQ(f.axis, 2);
}

// The depth alone, as the raster reads it at every texel (faceSampleAt, and the box's zOver): the
// face and the recess faceTextureAt gives and the height over() gives, to the bit, on every face,
// its edges and corners, and from every direction of the plane's downward.
TEST(TexturedBox, ItsDepthAloneIsTheDepthItsFullReadGives) {
  const tex::TextureMap map = heightMap(128, kExtent, vGrooves);
  FaceTexture faces;
  faces.map = &map;
  faces.tile_m = kExtent;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int compared = 0;
  for (int k = 0; k < 20000; ++k) {
    // A point on the surface (snapped to a face, an edge or a corner), a direction, a pose.
    Eigen::Vector3d p(unit(rng) * kHalf.x(), unit(rng) * kHalf.y(), unit(rng) * kHalf.z());
    const int snap = int(rng() % 3) + 1;
    for (int a = 0; a < snap; ++a) p[(k + a) % 3] = (unit(rng) < 0.0 ? -1.0 : 1.0) * kHalf[(k + a) % 3];
    const Eigen::Vector3d toward = Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized();
    const FacePoint full = faceTextureAt(faces, kHalf, p, toward), alone = faceSampleAt(faces, kHalf, p, toward).face;
    ASSERT_EQ(full.axis, alone.axis) << k;
    ASSERT_EQ(full.sign, alone.sign) << k;
    ASSERT_EQ(full.recess_m, alone.recess_m) << k;

    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::Quaterniond(Eigen::Vector4d(unit(rng), unit(rng), unit(rng), unit(rng)).normalized()).toRotationMatrix();
    pose.translation() = Eigen::Vector3d(0.003 * unit(rng), 0.003 * unit(rng), 0.02);
    const Underside box = Underside::box(pose, kHalf);
    const TexturedObjectSurface surface(box, faces);
    const Eigen::Vector2d xy(0.012 * unit(rng), 0.012 * unit(rng));
    const std::optional<double> z = lowestZ(box, xy.x(), xy.y());
    if (!z) continue;
    const ObjectSurfacePoint over = surface.over(xy.x(), xy.y(), *z);
    ASSERT_EQ(over.z, surface.zOver(xy.x(), xy.y(), *z)) << k;
    ++compared;
  }
  EXPECT_GT(compared, 5000);  // the box under enough of the points
}

// The raster reads a textured box row by row (textured_box_rows.hpp): its lowest point and its
// surface over each texel as lowestZ and TexturedObjectSurface read them, to rounding (the slabs'
// sines taken as reciprocals), and the same face; missing the box where lowestZ does. Poses at
// random and upright (axes parallel to the vertical's slabs, which bound nothing).
TEST(TexturedBox, ItsRowReaderGivesWhatItsPointReadsGive) {
  const tex::TextureMap map = heightMap(128, kExtent, vGrooves);
  FaceTexture faces;
  faces.map = &map;
  faces.tile_m = kExtent;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int hits = 0, misses = 0, candidates_like = 0;
  for (int pose_k = 0; pose_k < 60; ++pose_k) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    if (pose_k % 4 != 0)
      pose.linear() = Eigen::Quaterniond(Eigen::Vector4d(unit(rng), unit(rng), unit(rng), unit(rng)).normalized()).toRotationMatrix();
    else  // upright, turned about the vertical
      pose.linear() = Eigen::AngleAxisd(3.0 * unit(rng), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    pose.translation() = Eigen::Vector3d(0.003 * unit(rng), 0.003 * unit(rng), 0.02);
    const Underside box = Underside::box(pose, kHalf);
    const TexturedObjectSurface surface(box, faces);
    TexturedBoxRows rows(box, surface);
    for (int row = 0; row < 20; ++row) {
      const double y = 0.02 * unit(rng);
      rows.startRow(y);
      for (int k = 0; k < 40; ++k) {
        const double x = 0.02 * unit(rng);
        TexturedBoxRows::Point point;
        const bool hit = rows.at(x, point);
        const std::optional<double> z = lowestZ(box, x, y);
        ASSERT_EQ(hit, z.has_value()) << pose_k << " " << x << " " << y;
        if (!hit) {
          ++misses;
          continue;
        }
        ++hits;
        ASSERT_NEAR(point.lowest_z, *z, 1e-15);
        ASSERT_NEAR(point.surface.z, surface.zOver(x, y, *z), 1e-12);
        const ObjectSurfacePoint over = surface.over(x, y, *z);
        const std::optional<Eigen::Vector3d> up = rows.nUp(point);
        ASSERT_EQ(up.has_value(), over.n_up.has_value());
        if (up) {
          ASSERT_LT((*up - *over.n_up).norm(), 1e-9);
          ++candidates_like;
        }
      }
    }
  }
  EXPECT_GT(hits, 5000);
  EXPECT_GT(misses, 5000);
  EXPECT_GT(candidates_like, 2000);  // normals compared on faces not steep
}

}  // namespace
}  // namespace thx::phys::test::test_textured_box
