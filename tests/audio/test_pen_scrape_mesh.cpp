// The pen's scrape on a mesh scene's solid (issue 29; synthesis/scrape_sites.hpp,
// synthesis/pen_scrape.hpp): where it strikes, along what, and how the walk treats a curved
// surface and the uv's seams.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "clients/audio/analysis/surface_nodes.hpp"
#include "clients/audio/synthesis/pen_scrape.hpp"
#include "clients/audio/synthesis/scrape_sites.hpp"
#include "tests/audio/live_fixtures.hpp"

namespace thx::audio::test_pen_scrape_mesh {
namespace {

constexpr double kRadius = 0.03;

const TetMesh& ball() {
  static const TetMesh m = sphereMesh("ball", kRadius, 3, ElementOrder::Quadratic);
  return m;
}

// The ball's frame in the world: turned a quarter about x and moved, so a test that forgot to
// move the tip into the mesh's frame finds the wrong nodes.
Eigen::Isometry3d ballToWorld() {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translate(Eigen::Vector3d(0.1, -0.02, 0.2));
  t.rotate(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX()));
  return t;
}

int bruteNearest(const TetMesh& mesh, const std::vector<char>& allowed, const Eigen::Vector3d& p) {
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    if (!allowed[n]) continue;
    const double d = (mesh.nodes[n] - p).squaredNorm();
    if (d < best_d) best_d = d, best = int(n);
  }
  return best;
}

TEST(ScrapeSites, TheSlabsTopFaceIsFoundByUvAndStruckAlongItsNormal) {
  const TetMesh& slab = test::liveSlab().mesh;
  const ScrapeSites sites = ScrapeSites::slabTop(slab, {0.2, 0.2});
  std::vector<char> top(slab.nodes.size(), 0);
  for (std::size_t n = 0; n < slab.nodes.size(); ++n) top[n] = std::fabs(slab.nodes[n].z()) < 1e-12;
  EXPECT_FALSE(sites.onMesh());
  for (const tex::TexCoord uv : {tex::TexCoord{0.5, 0.5}, {0.13, 0.92}, {1.7, -0.3}}) {
    const double u = uv.u - std::floor(uv.u), v = uv.v - std::floor(uv.v);
    const int n = sites.nearest(uv, Eigen::Vector3d(9, 9, 9));  // the point is not read on the slab
    EXPECT_EQ(n, bruteNearest(slab, top, Eigen::Vector3d((u - 0.5) * 0.2, (v - 0.5) * 0.2, 0.0)));
    EXPECT_EQ(sites.direction(n), Eigen::Vector3d::UnitZ());
  }
  EXPECT_EQ(sites.initial(), sites.nearest({0.5, 0.5}, Eigen::Vector3d::Zero()));
}

TEST(ScrapeSites, AMeshSolidIsStruckAtTheSurfaceNodeNearestTheTipAlongItsOutwardNormal) {
  TetMesh mesh = ball();
  const SurfaceNodes surface = surfaceNodes(mesh);
  // Hold one surface node: it cannot move, so it is never struck.
  int held = -1;
  for (std::size_t n = 0; n < mesh.nodes.size() && held < 0; ++n)
    if (surface.on_surface[n] && mesh.nodes[n].z() > 0.9 * kRadius) held = int(n);
  ASSERT_GE(held, 0);
  mesh.clamped.assign(mesh.nodes.size(), 0);
  mesh.clamped[std::size_t(held)] = 1;
  std::vector<char> allowed = surface.on_surface;
  allowed[std::size_t(held)] = 0;

  const Eigen::Isometry3d to_world = ballToWorld();
  const ScrapeSites sites = ScrapeSites::meshSurface(mesh, to_world);
  EXPECT_TRUE(sites.onMesh());
  std::size_t surface_count = 0, interior = 0;
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    surface_count += allowed[n];
    if (!surface.on_surface[n]) {
      ++interior;
      EXPECT_EQ(sites.direction(int(n)), Eigen::Vector3d::Zero()) << n;
    }
  }
  ASSERT_GT(interior, 0u);
  EXPECT_EQ(sites.size(), surface_count);

  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  for (int k = 0; k < 300; ++k) {
    const Eigen::Vector3d dir = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    const Eigen::Vector3d in_mesh = dir * kRadius * (1.0 + 0.02 * g(rng));  // a little off the surface
    const int n = sites.nearest({0.3, 0.7}, to_world * in_mesh);            // the uv is not read on a mesh
    ASSERT_EQ(n, bruteNearest(mesh, allowed, in_mesh)) << k;
    EXPECT_NE(n, held);
    const Eigen::Vector3d& d = sites.direction(n);
    EXPECT_NEAR(d.norm(), 1.0, 1e-12);
    // Outward: along the radius through the node, within the facets' tilt.
    EXPECT_GT(d.dot(mesh.nodes[std::size_t(n)].normalized()), 0.9) << k;
  }
}

// A path on the ball's equator in the world (the mesh's frame moved by ballToWorld): the tip at
// 0.1 m/s, one sample per tick, the geometric normal radial, the tangent frame's u along the path.
std::vector<ScrapeSample> equatorPath(int ticks, double speed_m_s = 0.1) {
  std::vector<ScrapeSample> path;
  const Eigen::Isometry3d to_world = ballToWorld();
  for (int k = 0; k <= ticks; ++k) {
    const double phi = speed_m_s * k / 1000.0 / kRadius;
    const Eigen::Vector3d radial(std::cos(phi), std::sin(phi), 0.0), along(-std::sin(phi), std::cos(phi), 0.0);
    ScrapeSample s;
    s.tick = 500 + k;
    s.in_contact = true;
    s.uv = {phi * kRadius / 0.04, 0.25};
    s.f_normal_n = 1.0;
    s.n_geom = to_world.linear() * radial;
    s.n_contact = s.n_geom;
    s.v_tangent = to_world.linear() * along * speed_m_s;
    s.p_world = to_world * (kRadius * radial);
    path.push_back(s);
  }
  return path;
}

PenScrapeOptions meshOptions(MesoSource meso) {
  PenScrapeOptions o;
  o.surface_size_m = {0.04, 0.04};
  o.meso = meso;
  o.mesh_to_world = ballToWorld();
  return o;
}

struct Struck {
  std::vector<PenStrike> strikes;
  std::vector<PenMicroSegment> micro;
  std::size_t impulses = 0;
};

Struck scrape(const tex::TextureMap& map, const PenScrapeOptions& o, const std::vector<ScrapeSample>& path) {
  Struck out;
  PenScrape pen(map, ball(), o);
  for (const ScrapeSample& s : path)
    out.impulses += pen.next(
        s, [&](const PenStrike& p) { out.strikes.push_back(p); }, [&](const PenMicroSegment& m) { out.micro.push_back(m); });
  return out;
}

TEST(PenScrapeOnAMesh, ASmoothReliefOnACurvedSurfaceDoesNotClickButItsBumpsDo) {
  const tex::TextureMap relief(64, 64, tex::Representation::Relief, 0.001);
  std::vector<ScrapeSample> path = equatorPath(400);
  const Struck smooth = scrape(relief, meshOptions(MesoSource::ContactNormals), path);
  EXPECT_EQ(smooth.impulses, 400u);
  // The surface's normal turns 0.19° a tick; untransported that alone would be 1.5e-5 N s a tick.
  // Only rounding is left.
  double worst = 0.0;
  for (const PenStrike& p : smooth.strikes) worst = std::max(worst, std::fabs(p.impulse_ns));
  EXPECT_LT(worst, 1e-15);

  // A bump: the contact normal tilts 5° forward over ticks 200-209 (up the bump's far side).
  for (int k = 200; k < 210; ++k) {
    ScrapeSample& s = path[std::size_t(k)];
    const Eigen::Vector3d axis = s.n_geom.cross(s.v_tangent).normalized();
    s.n_contact = Eigen::AngleAxisd(5.0 * std::numbers::pi / 180.0, axis) * s.n_geom;
  }
  const Struck bump = scrape(relief, meshOptions(MesoSource::ContactNormals), path);
  std::size_t loud = 0;
  for (const PenStrike& p : bump.strikes) {
    if (std::fabs(p.impulse_ns) > 1e-9) {
      ++loud;
      EXPECT_TRUE(p.tick == 700 || p.tick == 710) << p.tick;  // onto the slope and off it
    }
  }
  EXPECT_EQ(loud, 2u);

  // Every segment strikes the solid's surface node nearest the tip.
  const ScrapeSites sites = ScrapeSites::meshSurface(ball(), ballToWorld());
  for (const PenMicroSegment& m : bump.micro)
    EXPECT_EQ(m.node, sites.nearest({}, path[std::size_t(m.tick_b - 500)].p_world));
}

TEST(PenScrapeOnAMesh, TheMicroLevelReadsTheDistanceTravelledOnTheSurface) {
  std::vector<ScrapeSample> path = equatorPath(100);
  for (ScrapeSample& s : path) s.uv.u *= 3.0;  // a stretched chart: uv no longer measures the path
  const Struck r = scrape(test::grooveMap(), meshOptions(MesoSource::TexelWalk), path);
  ASSERT_EQ(r.micro.size(), 100u);
  for (std::size_t k = 0; k < r.micro.size(); ++k)
    EXPECT_NEAR(r.micro[k].s1 - r.micro[k].s0, (path[k + 1].p_world - path[k].p_world).norm(), 1e-15);
}

TEST(PenScrapeOnAMesh, AWholeTileSeamIsWalkedAsIfTheUvWentOn) {
  // Across u = 1 at 0.1 m/s: a lathe's u going from its last tile back to 0 (a whole number of
  // tiles: the texture wraps, so the same texels follow).
  std::vector<ScrapeSample> unwrapped = equatorPath(300);
  const double shift = 1.0 - unwrapped[150].uv.u - 1e-7;
  for (ScrapeSample& s : unwrapped) s.uv.u += shift;
  ASSERT_LT(unwrapped[150].uv.u, 1.0);
  ASSERT_GT(unwrapped[151].uv.u, 1.0);
  std::vector<ScrapeSample> seamed = unwrapped;
  for (ScrapeSample& s : seamed)
    if (s.uv.u >= 1.0) s.uv.u -= 1.0;
  const Struck a = scrape(test::grooveMap(), meshOptions(MesoSource::TexelWalk), unwrapped);
  const Struck b = scrape(test::grooveMap(), meshOptions(MesoSource::TexelWalk), seamed);
  ASSERT_GT(a.strikes.size(), 10u);
  EXPECT_EQ(a.impulses, b.impulses);
  ASSERT_EQ(a.strikes.size(), b.strikes.size());
  for (std::size_t k = 0; k < a.strikes.size(); ++k) {
    EXPECT_EQ(a.strikes[k].tick, b.strikes[k].tick);
    EXPECT_EQ(a.strikes[k].node, b.strikes[k].node);
    EXPECT_NEAR(a.strikes[k].impulse_ns, b.strikes[k].impulse_ns, 1e-15);
  }
}

TEST(PenScrapeOnAMesh, AnyOtherSeamStartsTheWalkAgainWithoutABurst) {
  // At tick 150 the uv jumps 0.37 of a tile (a mesh file's seam) while the tip moves 0.1 mm: the
  // plane's walk would cross 23 texels at once. On a mesh that segment makes no impulse and the
  // walk starts again where the tip landed: the same strikes as the two halves scraped apart.
  std::vector<ScrapeSample> path = equatorPath(300);
  for (std::size_t k = 151; k < path.size(); ++k) path[k].uv.u += 0.37;
  const tex::TextureMap map = test::grooveMap();
  const PenScrapeOptions o = meshOptions(MesoSource::TexelWalk);
  const Struck whole = scrape(map, o, path);
  const Struck first = scrape(map, o, {path.begin(), path.begin() + 151});
  const Struck second = scrape(map, o, {path.begin() + 151, path.end()});
  ASSERT_GT(first.strikes.size(), 5u);
  ASSERT_GT(second.strikes.size(), 5u);
  ASSERT_EQ(whole.strikes.size(), first.strikes.size() + second.strikes.size());
  for (std::size_t k = 0; k < whole.strikes.size(); ++k) {
    const PenStrike& expected =
        k < first.strikes.size() ? first.strikes[k] : second.strikes[k - first.strikes.size()];
    EXPECT_EQ(whole.strikes[k].tick, expected.tick);
    EXPECT_EQ(whole.strikes[k].impulse_ns, expected.impulse_ns);
  }
  EXPECT_EQ(whole.impulses, first.impulses + second.impulses);
}

}  // namespace
}  // namespace thx::audio::test_pen_scrape_mesh
