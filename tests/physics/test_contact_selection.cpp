// contact_selection.*: which <= 4 rasterised relief contacts go into Bullet's manifold.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include "clients/physics/contact_selection.hpp"

namespace thx::phys::test_contact_selection {
namespace {

ReliefCandidate at(double x, double y, double depth) {
  ReliefCandidate c;
  c.p_surface = Eigen::Vector3d(x, y, 0.0);
  c.depth = depth;
  return c;
}

std::vector<std::size_t> select(const std::vector<ReliefCandidate>& c) {
  std::array<std::size_t, kMaxReliefContacts> chosen{};
  const std::size_t n = selectReliefContacts(c, chosen);
  EXPECT_LE(n, kMaxReliefContacts);
  return {chosen.begin(), chosen.begin() + long(n)};
}

std::set<std::pair<long, long>> positionsMm(const std::vector<ReliefCandidate>& c, const std::vector<std::size_t>& idx) {
  std::set<std::pair<long, long>> s;
  for (std::size_t k : idx) s.insert({std::lround(c[k].p_surface.x() * 1e3), std::lround(c[k].p_surface.y() * 1e3)});
  return s;
}

TEST(ContactSelection, NoCandidatesNoContacts) { EXPECT_TRUE(select({}).empty()); }

TEST(ContactSelection, OneCandidate) {
  const std::vector<std::size_t> s = select({at(0.001, 0.002, -1e-4)});
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0], 0u);
}

TEST(ContactSelection, TheDeepestComesFirst) {
  const std::vector<ReliefCandidate> c = {at(0, 0, -1e-5), at(0.003, 0, -2e-4), at(0.001, 0.002, -5e-5),
                                          at(-0.002, 0.001, 1e-6)};
  const std::vector<std::size_t> s = select(c);
  ASSERT_FALSE(s.empty());
  EXPECT_EQ(s[0], 1u);
}

TEST(ContactSelection, CoincidentCandidatesGiveOnePoint) {
  const std::vector<std::size_t> s = select({at(0.001, 0.001, -1e-5), at(0.001, 0.001, -3e-5), at(0.001, 0.001, 0.0)});
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0], 1u);
}

TEST(ContactSelection, CollinearCandidatesGiveTheDeepestAndTheFarthest) {
  // A cylinder lying along x: one line of texels. The deepest (middle) and the farthest end.
  std::vector<ReliefCandidate> c;
  for (int i = -5; i <= 5; ++i) c.push_back(at(0.001 * i, 0.002, i == 1 ? -2e-5 : -1e-5));
  const std::vector<std::size_t> s = select(c);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0], 6u);                       // x = 1 mm, the deepest
  EXPECT_NEAR(c[s[1]].p_surface.x(), -0.005, 1e-12);  // the far end from it
}

TEST(ContactSelection, AFlatBoxGetsItsFourCorners) {
  // A box resting flat: a grid of equally deep texels over its footprint (7 x 5, 1 mm apart),
  // one slightly deeper inside so the first pick is not a corner.
  std::vector<ReliefCandidate> c;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 7; ++i) c.push_back(at(0.001 * i, 0.001 * j, (i == 3 && j == 2) ? -1.1e-4 : -1e-4));
  const std::vector<std::size_t> s = select(c);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(c[s[0]].depth, -1.1e-4) << "the deepest first";
  // The remaining three together with the first span as much as possible: three corners of the
  // grid, and the convex hull of the four is the largest the grid allows with the centre point.
  const std::set<std::pair<long, long>> corners = {{0, 0}, {6, 0}, {0, 4}, {6, 4}};
  std::size_t on_corners = 0;
  for (std::size_t k = 1; k < 4; ++k)
    on_corners += corners.count({std::lround(c[s[k]].p_surface.x() * 1e3), std::lround(c[s[k]].p_surface.y() * 1e3)});
  EXPECT_EQ(on_corners, 3u) << "three more corners";
  EXPECT_EQ(positionsMm(c, s).size(), 4u) << "four distinct points";
}

TEST(ContactSelection, AFlatBoxWithoutADeeperPointGetsExactlyItsCorners) {
  std::vector<ReliefCandidate> c;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 7; ++i) c.push_back(at(0.001 * i, 0.001 * j, -1e-4));
  const std::vector<std::size_t> s = select(c);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(positionsMm(c, s), (std::set<std::pair<long, long>>{{0, 0}, {6, 0}, {0, 4}, {6, 4}}));
}

TEST(ContactSelection, ThreePointsThatSpanATriangleStayThree) {
  // Candidates on a triangle's vertices and edges only: no fourth point adds area.
  const std::vector<ReliefCandidate> c = {at(0, 0, -1e-4), at(0.004, 0, -1e-5), at(0, 0.004, -1e-5),
                                          at(0.002, 0, -1e-5), at(0, 0.002, -1e-5), at(0.002, 0.002, -1e-5)};
  const std::vector<std::size_t> s = select(c);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(positionsMm(c, s), (std::set<std::pair<long, long>>{{0, 0}, {4, 0}, {0, 4}}));
}

TEST(ContactSelection, ChosenIndicesAreDistinctAndValid) {
  std::vector<ReliefCandidate> c;
  unsigned state = 12345u;
  auto next = [&] { state = state * 1103515245u + 12345u; return double((state >> 8) & 0xffff) / 65535.0; };
  for (int trial = 0; trial < 50; ++trial) {
    c.clear();
    const int n = 1 + trial % 20;
    for (int k = 0; k < n; ++k) {
      // Drawn one by one: a call's arguments are evaluated in an unspecified order (g++ right to
      // left, clang left to right), which gave the two compilers different points. In this order
      // (clang's) trials 3, 25 and 43 draw four or more points of which three span them all.
      const double x = 0.01 * next(), y = 0.01 * next(), depth = -1e-4 * next();
      c.push_back(at(x, y, depth));
    }
    const std::vector<std::size_t> s = select(c);
    ASSERT_FALSE(s.empty());
    EXPECT_EQ(std::set<std::size_t>(s.begin(), s.end()).size(), s.size()) << "no index twice, trial " << trial;
    for (std::size_t k : s) EXPECT_LT(k, c.size());
    const auto deepest = std::min_element(c.begin(), c.end(), [](const auto& a, const auto& b) { return a.depth < b.depth; });
    EXPECT_EQ(s[0], std::size_t(deepest - c.begin()));
    if (n >= 4 && s.size() != 4u) {
      // Three only when no fourth adds area: every candidate inside the chosen triangle.
      ASSERT_EQ(s.size(), 3u) << "trial " << trial;
      const auto xy = [&](std::size_t k) { return Eigen::Vector2d(c[k].p_surface.head<2>()); };
      const Eigen::Vector2d a = xy(s[0]), b = xy(s[1]), d = xy(s[2]);
      const auto side = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v, const Eigen::Vector2d& p) {
        return (v - u).x() * (p - u).y() - (v - u).y() * (p - u).x();
      };
      const double orientation = side(a, b, d);
      for (std::size_t k = 0; k < c.size(); ++k) {
        const Eigen::Vector2d p = xy(k);
        EXPECT_GE(orientation * side(a, b, p), -1e-18) << "trial " << trial << ", candidate " << k;
        EXPECT_GE(orientation * side(b, d, p), -1e-18) << "trial " << trial << ", candidate " << k;
        EXPECT_GE(orientation * side(d, a, p), -1e-18) << "trial " << trial << ", candidate " << k;
      }
    }
  }
}

// A ball across a groove: a row of texels i = 0..10 (stride 2 apart when strided), two basins
// (the walls), the left one the deeper. The spread rule's fringe point on the right wall moves
// to that wall's bottom; a fringe point in the left wall's basin stays (look-ahead).
std::vector<ReliefCandidate> twoWalls(long long stride) {
  const double depth[11] = {3, 1, -2, 1, 4, 6, 4, 2, -1, 2, 5};  // µm: bottoms at i = 2 and i = 8
  std::vector<ReliefCandidate> c;
  for (long long i = 0; i <= 10; i += stride) {
    ReliefCandidate r = at(1e-3 * double(i), 0.0, 1e-6 * depth[i]);
    r.i = i;
    r.j = 7;
    c.push_back(r);
  }
  return c;
}

TEST(SnapToBasins, AFringePointOfAnotherBasinMovesToItsBottom) {
  const std::vector<ReliefCandidate> c = twoWalls(1);
  std::array<std::size_t, 3> chosen = {2, 10, 0};  // deepest, the far right fringe, the far left fringe
  snapToBasins(c, 1, 1, chosen);
  EXPECT_EQ(chosen[0], 2u);
  EXPECT_EQ(chosen[1], 8u) << "the right wall's bottom";
  EXPECT_EQ(chosen[2], 0u) << "in the deepest's basin: stays as look-ahead";
}

TEST(SnapToBasins, StridedCandidatesStepByTheStride) {
  const std::vector<ReliefCandidate> c = twoWalls(2);  // i = 0, 2, ..., 10 at indices 0..5
  std::array<std::size_t, 2> chosen = {1, 5};            // i = 2 (deepest), i = 10
  snapToBasins(c, 2, 2, chosen);
  EXPECT_EQ(c[chosen[1]].i, 8);
}

TEST(SnapToBasins, PlateausAndSingleCandidatesStay) {
  std::vector<ReliefCandidate> c = {at(0, 0, -1e-6), at(1e-3, 0, -1e-6)};
  c[1].i = 1;
  std::array<std::size_t, 2> chosen = {0, 1};
  snapToBasins(c, 1, 1, chosen);
  EXPECT_EQ(chosen[0], 0u);
  EXPECT_EQ(chosen[1], 1u) << "equal depths: no strictly lower neighbour";
}

// A rod along y lying in a V-groove: its lines of contact at x = -1 and +1 mm (depth -1 µm,
// the deeper at the left end), the walls' fringe farther out (x = +-2 mm, 100 µm gaps: where the
// spread rule went) and the groove's floor under the axis (50 µm), every 0.5 mm from y = -10 to 10.
std::vector<ReliefCandidate> rodInAGroove() {
  std::vector<ReliefCandidate> c;
  for (double y = -10.0; y <= 10.0 + 1e-9; y += 0.5) {
    c.push_back(at(-1e-3, y * 1e-3, -1e-6 + 1e-9 * y));
    c.push_back(at(1e-3, y * 1e-3, -1e-6));
    for (double x : {-2.0, 2.0}) c.push_back(at(x * 1e-3, y * 1e-3, 1e-4));
    c.push_back(at(0.0, y * 1e-3, 5e-5));
  }
  return c;
}

TEST(ContactSelection, ALyingRodTakesEachEndOfEachLineOfContact) {
  const std::vector<ReliefCandidate> c = rodInAGroove();
  std::array<std::size_t, kMaxReliefContacts> chosen{};
  const std::size_t n = selectLyingRodContacts(c, Eigen::Vector2d::Zero(), Eigen::Vector2d(0.0, 1.0), 7.5e-4, chosen);
  ASSERT_EQ(n, 4u);
  const std::vector<std::size_t> idx(chosen.begin(), chosen.begin() + 4);
  EXPECT_EQ(positionsMm(c, idx), (std::set<std::pair<long, long>>{{-1, -10}, {-1, 10}, {1, -10}, {1, 10}}));
  // Deepest first: the left line's far end (y = -10 mm).
  EXPECT_EQ(positionsMm(c, {chosen[0]}), (std::set<std::pair<long, long>>{{-1, -10}}));
  for (std::size_t k = 1; k < n; ++k) EXPECT_LE(c[chosen[k - 1]].depth, c[chosen[k]].depth);
  // The spread rule, for comparison, takes the fringe up the walls.
  const std::vector<std::size_t> spread = select(c);
  long fringe = 0;
  for (std::size_t k : spread) fringe += std::fabs(c[k].p_surface.x()) > 1.5e-3;
  EXPECT_GE(fringe, 2);
}

TEST(ContactSelection, ARodSteeperThanSixtyDegreesTakesTheGeneralRule) {
  const std::vector<ReliefCandidate> c = rodInAGroove();
  std::array<std::size_t, kMaxReliefContacts> chosen{};
  // Tilted 70 degrees: its axis's shadow on the plane is cos 70 = 0.34 long.
  EXPECT_EQ(selectLyingRodContacts(c, Eigen::Vector2d::Zero(), Eigen::Vector2d(0.0, 0.34), 7.5e-4, chosen), 0u);
  EXPECT_EQ(selectLyingRodContacts({}, Eigen::Vector2d::Zero(), Eigen::Vector2d(0.0, 1.0), 7.5e-4, chosen), 0u);
}

// The basins closest to closing (selectShallowestBasins): on a grid of candidates whose depth has
// five local minima (one of them a flat pair of equal texels) and a slope, the four shallowest
// minima, the deepest first; the fifth, deeper-open one is left out, and the flat pair counts once.
// With room for more (a ball keeps up to twelve), all five, and the floor's lowest corner (its
// missing neighbours open), and no other texel of the slope.
TEST(ShallowestBasins, TheBasinsClosestToClosingDeepestFirstAsManyAsThereIsRoomFor) {
  std::vector<ReliefCandidate> c;
  // depth(i, j): a tilted floor (every texel on it has a lower neighbour) with dips carved in.
  auto depth = [](long long i, long long j) {
    if (i == 2 && j == 2) return -5e-6;                 // the deepest
    if (i == 7 && j == 2) return 3e-6;                  // a tip 3 um open
    if ((i == 2 || i == 3) && j == 7) return 1e-6;      // a flat pair, 1 um open
    if (i == 8 && j == 8) return 8e-6;                  // 8 um open
    if (i == 5 && j == 5) return 20e-6;                 // 20 um open: the fifth
    return 40e-6 + 1e-6 * double(i + j);                // the floor, rising with i + j
  };
  for (long long j = 0; j < 10; ++j)
    for (long long i = 0; i < 10; ++i) {
      ReliefCandidate k = at(1e-4 * double(i), -1e-4 * double(j), depth(i, j));
      k.i = i, k.j = j;
      c.push_back(k);
    }
  std::array<std::size_t, kMaxReliefContacts> chosen{};
  const std::size_t n = selectShallowestBasins(c, 1, 1, chosen);
  ASSERT_EQ(n, 4u);
  auto ij = [&](std::size_t k) { return std::make_pair(c[chosen[k]].i, c[chosen[k]].j); };
  EXPECT_EQ(ij(0), std::make_pair(2LL, 2LL));
  EXPECT_EQ(ij(1), std::make_pair(2LL, 7LL));  // the flat pair's first texel, once
  EXPECT_EQ(ij(2), std::make_pair(7LL, 2LL));
  EXPECT_EQ(ij(3), std::make_pair(8LL, 8LL));
  std::array<std::size_t, 12> roomy{};
  roomy.fill(c.size());
  ASSERT_EQ(selectShallowestBasins(c, 1, 1, roomy), 6u);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(roomy[k], chosen[k]) << k;
  EXPECT_EQ(std::make_pair(c[roomy[4]].i, c[roomy[4]].j), std::make_pair(5LL, 5LL));
  EXPECT_EQ(std::make_pair(c[roomy[5]].i, c[roomy[5]].j), std::make_pair(0LL, 0LL));  // the floor's low corner
  for (std::size_t k = 6; k < roomy.size(); ++k) EXPECT_EQ(roomy[k], c.size()) << "slot " << k << " written";
  // On a strided grid (every second texel) the same basins are found among the texels read.
  std::vector<ReliefCandidate> strided;
  for (const ReliefCandidate& k : c)
    if (k.i % 2 == 0 && k.j % 2 == 0) strided.push_back(k);
  const std::size_t m = selectShallowestBasins(strided, 2, 2, chosen);
  ASSERT_GE(m, 2u);
  EXPECT_EQ(std::make_pair(strided[chosen[0]].i, strided[chosen[0]].j), std::make_pair(2LL, 2LL));
  EXPECT_EQ(std::make_pair(strided[chosen[1]].i, strided[chosen[1]].j), std::make_pair(8LL, 8LL));
  EXPECT_EQ(selectShallowestBasins(std::vector<ReliefCandidate>{}, 1, 1, chosen), 0u);
}

}  // namespace
}  // namespace thx::phys::test_contact_selection
