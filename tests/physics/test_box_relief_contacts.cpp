// A box on a relief: the row-by-row rule (box_relief_contacts.hpp) chooses the contacts the
// general rule chooses (rasterise every texel, the quarter rule over all of them), on flat, bumpy
// and bricked reliefs, in every pose a box can rest or tumble in, both address modes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "clients/physics/box_relief_contacts.hpp"
#include "physics_fixtures.hpp"
#include "textures/height_normals.hpp"

namespace thx::phys::test::test_box_relief_contacts {
namespace {

constexpr double kExtent = 0.125;     // 256 texels of 0.49 mm: the 1024² benchmark's texel
constexpr double kThreshold = 3.46e-4;  // the box's manifold breaking threshold in the worlds

enum class Relief { Flat, Bumps, Bricks };

SurfaceHolder reliefOf(Relief kind, tex::Address address) {
  const int n = 256;
  const double d = kExtent / n;
  tex::HeightField field;
  field.width = field.height = n;
  field.heights_m.assign(std::size_t(n) * n, 0.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = (i + 0.5) * d, y = (j + 0.5) * d;
      double h = 0.0;
      if (kind == Relief::Bumps) h = 4e-4 * std::sin(2 * M_PI * x / 0.007) * std::sin(2 * M_PI * y / 0.011);
      // Bricks 12 x 6 mm with 1 mm joints 0.6 mm deep: flat tops, steps at the joints.
      if (kind == Relief::Bricks) h = std::fmod(x, 0.012) < 0.001 || std::fmod(y, 0.006) < 0.001 ? -6e-4 : 0.0;
      field.heights_m[std::size_t(j) * n + std::size_t(i)] = h;
    }
  tex::ReliefFromHeightOptions o;
  o.texel_m = {d, d};
  o.address = address;
  return holdSurface(tex::reliefFromHeight(field, o), kExtent, true, address);
}

std::string describe(const ChosenReliefContacts& c) {
  std::string s = std::to_string(c.count) + " contacts:";
  for (std::size_t k = 0; k < c.count; ++k)
    s += " (" + std::to_string(c.contacts[k].i) + "," + std::to_string(c.contacts[k].j) + ")";
  return s;
}

// Same texels, same points and normals to the bit, depths equal to rounding.
void expectSameContacts(const ChosenReliefContacts& rows, const ChosenReliefContacts& general, const std::string& where) {
  ASSERT_EQ(rows.count, general.count) << where << "\n rows " << describe(rows) << "\n general " << describe(general);
  for (std::size_t k = 0; k < rows.count; ++k) {
    const ReliefCandidate &a = rows.contacts[k], &b = general.contacts[k];
    ASSERT_TRUE(a.i == b.i && a.j == b.j) << where << " contact " << k << "\n rows " << describe(rows) << "\n general "
                                          << describe(general);
    EXPECT_EQ(a.p_surface, b.p_surface) << where;
    EXPECT_EQ(a.n_local, b.n_local) << where;
    EXPECT_NEAR(a.depth, b.depth, 1e-15) << where;
  }
}

// A box of half side `half` turned by `turn`, its lowest corner `sink` below the relief's top (z = 0).
Underside boxAt(const Eigen::Vector2d& xy, const Eigen::Matrix3d& turn, double half, double sink) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = turn;
  const double reach = (turn.cwiseAbs() * Eigen::Vector3d::Constant(half)).z();
  pose.translation() = Eigen::Vector3d(xy.x(), xy.y(), reach - sink);
  return Underside::box(pose, Eigen::Vector3d::Constant(half));
}

TEST(BoxReliefContacts, ChoosesTheGeneralRulesContactsInRandomPoses) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int compared = 0, touching = 0;
  for (tex::Address address : {tex::Address::Clamp, tex::Address::Wrap}) {
    for (Relief kind : {Relief::Flat, Relief::Bumps, Relief::Bricks}) {
      const SurfaceHolder s = reliefOf(kind, address);
      const ReliefLevelRuns level(*s.map);
      for (int k = 0; k < 120; ++k) {
        // Anywhere on the map and across its edge (the wrap seam, the clamped border), tilted
        // up to 40° (some poses a resting box has, most a tumbling one), sunk up to 0.4 mm.
        const Eigen::Vector2d xy(0.07 * unit(rng), 0.07 * unit(rng));
        const double tilt = 0.7 * std::fabs(unit(rng)), yaw = M_PI * unit(rng);
        const Eigen::Vector3d axis = Eigen::Vector3d(unit(rng), unit(rng), 0.0).normalized();
        const Eigen::Matrix3d turn =
            (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(tilt, axis)).toRotationMatrix();
        const Underside box = boxAt(xy, turn, 0.004 + 0.008 * std::fabs(unit(rng)), 4e-4 * std::fabs(unit(rng)));
        // Texel by texel, and with the level stretches read at their ends.
        ChosenReliefContacts rows, stretches;
        ASSERT_TRUE(boxReliefContacts(s.surface, box, kThreshold, rows));
        ASSERT_TRUE(boxReliefContacts(s.surface, box, kThreshold, stretches, &level));
        const ChosenReliefContacts general = generalBoxReliefContacts(s.surface, box, kThreshold);
        const std::string where = "pose " + std::to_string(k) + " relief " + std::to_string(int(kind));
        expectSameContacts(rows, general, where + ", texel by texel");
        expectSameContacts(stretches, general, where + ", level stretches");
        ++compared;
        touching += rows.count > 0;
      }
    }
  }
  EXPECT_EQ(compared, 720);
  EXPECT_GT(touching, 600);  // the poses do touch
}

TEST(BoxReliefContacts, ALevelBoxAndANearlyLevelOneGetTheGeneralRulesCorners) {
  // The resting box of the benchmark: level to float rounding. Axis-aligned, every texel under
  // it is equally deep and its side faces stand vertical: the first texel in scan order is the
  // deepest for both rules.
  const SurfaceHolder s = reliefOf(Relief::Flat, tex::Address::Clamp);
  const ReliefLevelRuns level(*s.map);
  for (double tilt : {0.0, 1e-9, 1e-6, 1e-3}) {
    for (double yaw : {0.0, 0.3}) {
      const Eigen::Matrix3d turn = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(tilt, Eigen::Vector3d(0.6, 0.8, 0.0)))
                                       .toRotationMatrix();
      const Underside box = boxAt({0.013, 0.007}, turn, 0.0105, 1e-8);
      ChosenReliefContacts rows, stretches;
      ASSERT_TRUE(boxReliefContacts(s.surface, box, kThreshold, rows));
      ASSERT_TRUE(boxReliefContacts(s.surface, box, kThreshold, stretches, &level));
      const ChosenReliefContacts general = generalBoxReliefContacts(s.surface, box, kThreshold);
      const std::string where = "tilt " + std::to_string(tilt) + " yaw " + std::to_string(yaw);
      expectSameContacts(rows, general, where + ", texel by texel");
      expectSameContacts(stretches, general, where + ", level stretches");
      EXPECT_EQ(rows.count, 4u);  // its four corners
    }
  }
}

TEST(BoxReliefContacts, ANearlyLevelBoxGetsTheGeneralRulesContacts) {
  // Resting poses: tilted by 1e-9 to 1e-3 rad about any level axis, a third of them square to
  // the texels and the others at any yaw, on the flat relief and on the bricks. On level stretches
  // the row-by-row path reads only the ends of where one face is lowest, of each quarter's part
  // and of the part within the depth step of the deepest: all three change within a stretch in
  // these poses (the depth step of a flat relief is 0: there the part is the deepest's own level).
  std::mt19937 rng(2912);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int four = 0, compared = 0;
  for (tex::Address address : {tex::Address::Clamp, tex::Address::Wrap}) {
    for (Relief kind : {Relief::Flat, Relief::Bricks}) {
      const SurfaceHolder s = reliefOf(kind, address);
      const ReliefLevelRuns level(*s.map);
      for (int k = 0; k < 150; ++k) {
        const Eigen::Vector2d xy(0.07 * unit(rng), 0.07 * unit(rng));
        const double tilt = std::pow(10.0, -3.0 - 6.0 * std::fabs(unit(rng))), yaw = M_PI * unit(rng);
        const Eigen::Vector3d axis = Eigen::Vector3d(unit(rng), unit(rng), 0.0).normalized();
        const Eigen::Matrix3d turn =
            (Eigen::AngleAxisd(k % 3 == 0 ? 0.0 : yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(tilt, axis))
                .toRotationMatrix();
        const Underside box = boxAt(xy, turn, 0.003 + 0.008 * std::fabs(unit(rng)), 1e-7 + 4e-5 * std::fabs(unit(rng)));
        ChosenReliefContacts stretches;
        ASSERT_TRUE(boxReliefContacts(s.surface, box, kThreshold, stretches, &level));
        const ChosenReliefContacts general = generalBoxReliefContacts(s.surface, box, kThreshold);
        expectSameContacts(stretches, general, "pose " + std::to_string(k) + " relief " + std::to_string(int(kind)));
        four += stretches.count == 4;
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 600);
  EXPECT_GT(four, 500);  // a point in each quarter
}

TEST(BoxReliefContacts, OnABrickByItsCentreTheDeepestQuarterTakesTheFarthestTexelWithinTheDepthStep) {
  // A box touching only a brick raised 0.6 mm in one quarter of its footprint, tilted a few
  // micro-radians down towards its centre: the deepest texel is the brick's end nearest the
  // centre, and within the depth step (9 nm) of it lie a few texels farther out along each row.
  // The farthest of them wins that quarter: on its level stretch it is neither the stretch's end
  // nor by a crossing of faces or quarters, but the end of the part within the step.
  const int n = 256;
  const double d = kExtent / n;
  tex::HeightField field;
  field.width = field.height = n;
  field.heights_m.assign(std::size_t(n) * n, -6e-4);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = (i + 0.5) * d - 0.5 * kExtent, y = 0.5 * kExtent - (j + 0.5) * d;
      if (x > 0.002 && x < 0.008 && y > 0.002 && y < 0.008) field.heights_m[std::size_t(j) * n + std::size_t(i)] = 0.0;
    }
  tex::ReliefFromHeightOptions o;
  o.texel_m = {d, d};
  const SurfaceHolder s = holdSurface(tex::reliefFromHeight(field, o), kExtent, true);
  ASSERT_GT(s.map->depthStep(), 0.0);
  const ReliefLevelRuns level(*s.map);
  int within_step_won = 0;
  for (double tilt : {2e-6, 5e-6, 1e-5}) {
    // Down towards -x and -y: the brick's corner nearest the box's centre is the deepest.
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(tilt, Eigen::Vector3d(1.0, -0.7, 0.0).normalized()).toRotationMatrix();
    const Underside box = boxAt({0.0, 0.0}, turn, 0.01, 1e-7);  // its lowest point 0.1 um into the brick
    ChosenReliefContacts stretches;
    ASSERT_TRUE(boxReliefContacts(s.surface, box, kThreshold, stretches, &level));
    const ChosenReliefContacts general = generalBoxReliefContacts(s.surface, box, kThreshold);
    expectSameContacts(stretches, general, "tilt " + std::to_string(tilt));
    ASSERT_EQ(stretches.count, 1u);  // one quarter touches
    const ReliefCandidate& c = stretches.contacts[0];
    // Not the brick's corner nearest the centre (the deepest), farther out within the step.
    within_step_won += c.p_surface.x() > 0.0025 || c.p_surface.y() > 0.0025;
  }
  EXPECT_EQ(within_step_won, 3);
}

TEST(BoxReliefContacts, LevelRunsCountEqualDepthsAlongARowUpToItsEdge) {
  tex::HeightField field;
  field.width = 6, field.height = 2;
  field.heights_m = {0, 0, 0, -1e-3, -1e-3, 0,  // two stretches and a lone texel
                     0, 0, 0, 0, 0, 0};         // one stretch: it stops at the edge, no wrap
  tex::ReliefFromHeightOptions o;
  o.texel_m = {1e-3, 1e-3};
  const ReliefLevelRuns runs(tex::reliefFromHeight(field, o));
  const std::vector<long long> want = {3, 2, 1, 2, 1, 1, 6, 5, 4, 3, 2, 1};
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 6; ++i) EXPECT_EQ(runs.levelAlong(i, j), want[std::size_t(j * 6 + i)]) << i << "," << j;
}

TEST(BoxReliefContacts, ABoxAboveTheReliefHasNoneAndAHugeOneIsLeftToTheGeneralRule) {
  const SurfaceHolder s = reliefOf(Relief::Bumps, tex::Address::Wrap);
  ChosenReliefContacts rows;
  ASSERT_TRUE(boxReliefContacts(s.surface, boxAt({0, 0}, Eigen::Matrix3d::Identity(), 0.01, -0.002), kThreshold, rows));
  EXPECT_EQ(rows.count, 0u);
  // More texels under it than kMaxFootprintTexels: visited with a stride, by the general rule.
  EXPECT_FALSE(boxReliefContacts(s.surface, boxAt({0, 0}, Eigen::Matrix3d::Identity(), 0.2, 1e-4), kThreshold, rows));
}

}  // namespace
}  // namespace thx::phys::test::test_box_relief_contacts
