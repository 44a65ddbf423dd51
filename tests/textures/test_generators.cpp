// Procedural relief maps (textures/generators.hpp): normals agree with the stored depth, analytic
// cases are exact, seeding is deterministic, bad requests are explained.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "textures/generators.hpp"
#include "textures/texture_error.hpp"

namespace test_generators {

using namespace thx::tex;

namespace {

constexpr double kPi = 3.14159265358979323846;
const char* const kKinds[] = {"bricks", "vvalley", "grooves", "pebbles", "wood", "sine", "dimples", "tilted", "zigzag",
                              "porcelain", "metal", "stone", "ceramic_tile"};

TextureMap make(const std::string& kind, int size, std::map<std::string, double> params = {}, std::uint64_t seed = 1) {
  GenerateRequest r;
  r.kind = kind;
  r.size = size;
  r.params = std::move(params);
  r.seed = seed;
  return generate(r);
}

// Slopes (dh/dx, dh/dy) encoded by the stored normal.
Eigen::Vector2d slopeOf(const TextureMap& m, int i, int j) {
  const Eigen::Vector3d n = m.normal(i, j).cast<double>();
  return {-n.x() / n.z(), -n.y() / n.z()};
}

double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

bool identical(const TextureMap& a, const TextureMap& b) {
  if (a.width() != b.width() || a.height() != b.height() || a.maxDepth() != b.maxDepth()) return false;
  for (int j = 0; j < a.height(); ++j)
    for (int i = 0; i < a.width(); ++i)
      if (a.depthCode(i, j) != b.depthCode(i, j) || a.normal(i, j) != b.normal(i, j)) return false;
  return true;
}

struct Consistency {
  long tested = 0, skipped = 0, failed = 0;
  long flip_caught = 0;  // tested texels where a mirrored x or y slope would have failed
  double max_error = 0.0;      // slope units
  double max_tolerance = 0.0;  // slope units
  double sum_error = 0.0;
};

// Compares, at interior texels, the slopes the normals encode with central differences of the
// stored depth (h = -depth; +y = up = row j-1). Along each axis, with s the normal's slope,
// D2 = s(+1) - 2 s(0) + s(-1) and D3 the larger of the two third differences over s(-2..+2):
//
//  - Skipped: texels where D3 > max(2e-3 (1 + |s|^2), max|D1| / 2), D1 = first differences over
//    the five texels. On a smooth surface with features of wavenumber k, D3 ~ (k d)^2 D1 << D1;
//    at a crease or kink (V floors and ridges, dimple and pebble rims, mortar corners) the slope
//    or curvature jumps and D3 is as large as D1 itself, and a feature too tight for the grid
//    (k d ~ 1) looks the same. There no single slope exists for a two-texel difference to match.
//    The 2e-3 (1 + |s|^2) floor is well above the snorm16 noise of D3, 8 x 3e-5 x (1 + |s|^2).
//  - Tolerance elsewhere, per axis, in slope units:
//     depth quantisation: each depth is within half a code (q = maxDepth / 65535) of the true
//       one, so the difference quotient is off by at most q / (2 d); allow q / d;
//     normal quantisation (snorm16): 1e-4 (1 + |s|^2);
//     finite differences: (h(+1) - h(-1)) / 2d is the mean slope over the two texels around the
//       centre, i.e. s + d^2 h'''/6 ~ s + D2/6 on a smooth surface; allow |D2|/2 (margin for the
//       D2 estimate itself). A kink too small to be skipped is off by at most half its slope
//       jump, which D3 (>= the jump) covers: + D3.
Consistency checkConsistency(const TextureMap& m, double texel_m) {
  Consistency c;
  const double q = m.maxDepth() / 65535.0;
  const int w = m.width();
  std::vector<Eigen::Vector2d> slopes;  // decoded once: this runs under ASan too
  std::vector<double> depths;
  for (int j = 0; j < m.height(); ++j)
    for (int i = 0; i < w; ++i) {
      slopes.push_back(slopeOf(m, i, j));
      depths.push_back(m.depth(i, j));
    }
  auto at = [w](int i, int j) { return std::size_t(j) * std::size_t(w) + std::size_t(i); };
  for (int j = 2; j + 2 < m.height(); ++j) {
    for (int i = 2; i + 2 < w; ++i) {
      const Eigen::Vector2d s = slopes[at(i, j)];
      const Eigen::Vector2d fd(-(depths[at(i + 1, j)] - depths[at(i - 1, j)]) / (2 * texel_m),
                               -(depths[at(i, j - 1)] - depths[at(i, j + 1)]) / (2 * texel_m));
      bool skip = false, fail = false, flip = false;
      double tol[2], err[2];
      for (int axis = 0; axis < 2; ++axis) {
        double v[5];  // slopes along the axis, in its + direction (+y = decreasing row)
        for (int k = -2; k <= 2; ++k) v[k + 2] = axis == 0 ? slopes[at(i + k, j)].x() : slopes[at(i, j - k)].y();
        const double d2 = v[3] - 2 * v[2] + v[1];
        const double d3 = std::max(std::fabs(v[3] - 3 * v[2] + 3 * v[1] - v[0]),
                                   std::fabs(v[4] - 3 * v[3] + 3 * v[2] - v[1]));
        double d1 = 0.0;
        for (int k = 0; k < 4; ++k) d1 = std::max(d1, std::fabs(v[k + 1] - v[k]));
        skip |= d3 > std::max(2e-3 * (1 + s.squaredNorm()), 0.5 * d1);
        tol[axis] = q / texel_m + 1e-4 * (1 + s.squaredNorm()) + std::fabs(d2) / 2 + d3;
        err[axis] = std::fabs(fd[axis] - s[axis]);
        fail |= err[axis] > tol[axis];
        flip |= std::fabs(fd[axis] + s[axis]) > tol[axis];
      }
      if (skip) {
        ++c.skipped;
        continue;
      }
      ++c.tested;
      c.flip_caught += flip;
      c.sum_error += std::max(err[0], err[1]);
      c.max_error = std::max({c.max_error, err[0], err[1]});
      c.max_tolerance = std::max({c.max_tolerance, tol[0], tol[1]});
      if (fail) {
        if (c.failed < 5) {
          ADD_FAILURE() << "texel (" << i << ", " << j << "): normal slope (" << s.x() << ", " << s.y()
                        << "), depth differences (" << fd.x() << ", " << fd.y() << "), tolerance (" << tol[0]
                        << ", " << tol[1] << ")";
        }
        ++c.failed;
      }
    }
  }
  return c;
}

std::string errorOf(const GenerateRequest& r) {
  try {
    generate(r);
  } catch (const TextureError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(Generators, SpecsListEveryKindWithSaneDefaults) {
  ASSERT_EQ(generatorSpecs().size(), std::size(kKinds));
  for (const char* kind : kKinds) {
    const GeneratorSpec* spec = findGenerator(kind);
    ASSERT_NE(spec, nullptr) << kind;
    bool has_extent = false;
    for (const GeneratorParam& p : spec->params) {
      EXPECT_LE(p.min_value, p.default_value) << kind << "." << p.name;
      EXPECT_GE(p.max_value, p.default_value) << kind << "." << p.name;
      EXPECT_FALSE(p.unit.empty()) << kind << "." << p.name;
      has_extent |= p.name == "extent";
    }
    EXPECT_TRUE(has_extent) << kind;
  }
  EXPECT_EQ(findGenerator("nope"), nullptr);
}

// Every generator at its defaults on a 25 mm patch at 256^2 (0.098 mm texels, so the mm-scale
// features span tens of texels and most of each map is smooth at the texel scale).
// min_tested: the share of interior texels that must be away from creases (V-valleys have one
// every 20 texels; sine, wood and tilted have none). min_caught: the share of tested texels at
// which the check would notice a mirrored slope (a wrong sign or axis convention): it proves the
// tolerance is tight where the surface slopes (bricks and pebbles are mostly flat faces/ground).
struct ConsistencyCase {
  const char* kind;
  double min_tested, min_caught;
};

void expectConsistentAtDefaults(const ConsistencyCase& k) {
  const int n = 256;
  const double extent = 0.025, texel = extent / n;
  const TextureMap m = make(k.kind, n, {{"extent", extent}});
  ASSERT_TRUE(m.isRelief());
  const Consistency c = checkConsistency(m, texel);
  const double interior = double(n - 4) * (n - 4);
  std::printf("[ generators ] %-8s max depth %.3g mm: tested %.1f %% of interior texels (skipped %ld near "
              "creases), max slope error %.2e (mean %.2e), largest tolerance %.2e, mirrored slope caught at "
              "%.1f %%\n",
              k.kind, m.maxDepth() * 1e3, 100 * double(c.tested) / interior, c.skipped, c.max_error,
              c.sum_error / double(c.tested), c.max_tolerance, 100 * double(c.flip_caught) / double(c.tested));
  EXPECT_EQ(c.failed, 0) << k.kind;
  EXPECT_GE(double(c.tested), k.min_tested * interior) << k.kind;
  EXPECT_GE(double(c.flip_caught), k.min_caught * double(c.tested)) << k.kind;
}

TEST(Generators, NormalsAgreeWithTheirOwnDepth) {
  const ConsistencyCase cases[] = {{"bricks", 0.9, 0.1},  {"vvalley", 0.75, 0.99}, {"grooves", 0.85, 0.4},
                                   {"pebbles", 0.9, 0.2}, {"wood", 1.0, 0.5},      {"sine", 1.0, 0.9},
                                   {"dimples", 0.9, 0.2}, {"tilted", 1.0, 0.99},   {"zigzag", 0.95, 0.3}};
  for (const ConsistencyCase& k : cases) expectConsistentAtDefaults(k);
}

// The study surfaces' generators, the same way (a test of their own keeps each short under the
// sanitizers). Cracks, grout corners and scratches a few texels wide are skipped like creases.
TEST(SurfaceGenerators, NormalsAgreeWithTheirOwnDepth) {
  const ConsistencyCase cases[] = {{"porcelain", 0.75, 0.6}, {"metal", 0.5, 0.05}, {"stone", 0.85, 0.95},
                                   {"ceramic_tile", 0.85, 0.5}};
  for (const ConsistencyCase& k : cases) expectConsistentAtDefaults(k);
}

TEST(Generators, SameSeedSameMapDifferentSeedDifferentMap) {
  for (const char* kind : kKinds) {
    const TextureMap a = make(kind, 96, {}, 42), b = make(kind, 96, {}, 42), c = make(kind, 96, {}, 43);
    EXPECT_TRUE(identical(a, b)) << kind;
    const std::string k = kind;
    const bool seeded = k == "bricks" || k == "pebbles" || k == "wood" || k == "porcelain" || k == "metal" ||
                        k == "stone" || k == "ceramic_tile";
    EXPECT_EQ(identical(a, c), !seeded) << kind;
  }
}

// Walls rise at alpha = 90° - opening/2; the wall descending towards +x has the normal
// (sin alpha, 0, cos alpha). 60° opening, 4 mm period, 20 texels per period so no texel centre
// sits on a ridge or floor.
TEST(Generators, VValleyWallsHaveTheAnalyticNormal) {
  const double period = 0.004, alpha = (90.0 - 60.0 / 2) * kPi / 180;
  const int n = 200;
  const double extent = 0.04, d = extent / n;
  const TextureMap m = make("vvalley", n, {{"angle_deg", 60}, {"period", period}, {"extent", extent}});
  EXPECT_NE(m.meta().params.find("depth=" + std::to_string(period / 2 * std::tan(alpha)).substr(0, 6)),
            std::string::npos)
      << m.meta().params;
  double worst = 0.0;
  for (int j = 0; j < n; j += 7) {
    for (int i = 0; i < n; ++i) {
      const double f = std::fmod((i + 0.5) * d / period, 1.0);
      const double sign = f < 0.5 ? 1.0 : -1.0;
      const Eigen::Vector3d expected(sign * std::sin(alpha), 0, std::cos(alpha));
      worst = std::max(worst, angleBetween(m.normal(i, j).cast<double>(), expected));
      // Depth below the highest sampled point (ridge-adjacent texel centre, f = 0.025).
      const double depth = std::tan(alpha) * period * (std::min(f, 1 - f) - 0.025);
      EXPECT_NEAR(m.depth(i, j), depth, 2 * m.maxDepth() / 65535) << i << "," << j;
    }
  }
  EXPECT_LT(worst, 1e-4);  // snorm16 storage
}

TEST(Generators, TiltedPlaneHasTheAnalyticNormal) {
  const double a = 20 * kPi / 180, dir = 30 * kPi / 180;
  const TextureMap m = make("tilted", 64, {{"angle_deg", 20}, {"direction_deg", 30}, {"extent", 0.1}});
  const Eigen::Vector3d expected(std::sin(a) * std::cos(dir), std::sin(a) * std::sin(dir), std::cos(a));
  // Depth grows downhill, towards +x and +y (row 0 is +y).
  const double d = 0.1 / 64;
  for (int j = 0; j < 64; ++j) {
    for (int i = 0; i < 64; ++i) {
      EXPECT_LT(angleBetween(m.normal(i, j).cast<double>(), expected), 1e-4);
      const double along = i * d * std::cos(dir) + (63 - j) * d * std::sin(dir);
      EXPECT_NEAR(m.depth(i, j), std::tan(a) * along, 2 * m.maxDepth() / 65535);
    }
  }
}

TEST(Generators, MetadataNamesKindExtentAndParameters) {
  const TextureMap m = make("grooves", 32, {{"width", 0.003}, {"extent", 0.1}}, 7);
  EXPECT_EQ(m.meta().kind, "grooves");
  EXPECT_DOUBLE_EQ(m.meta().extent_x_m, 0.1);
  EXPECT_DOUBLE_EQ(m.meta().extent_y_m, 0.1);
  EXPECT_NE(m.meta().params.find("width=0.003"), std::string::npos) << m.meta().params;
  EXPECT_NE(m.meta().params.find("period=0.008"), std::string::npos) << m.meta().params;
  EXPECT_NE(m.meta().params.find("seed=7"), std::string::npos) << m.meta().params;
}

TEST(Generators, BadRequestsNameTheParameterAndValue) {
  GenerateRequest r;
  r.size = 16;

  r.kind = "brickz";
  std::string m = errorOf(r);
  EXPECT_NE(m.find("brickz"), std::string::npos) << m;
  EXPECT_NE(m.find("bricks, vvalley, grooves"), std::string::npos) << m;

  r.kind = "bricks";
  r.params = {{"mortar_width", 0.002}};
  m = errorOf(r);
  EXPECT_NE(m.find("generator bricks"), std::string::npos) << m;
  EXPECT_NE(m.find("mortar_width=0.002"), std::string::npos) << m;
  EXPECT_NE(m.find("mortar_depth"), std::string::npos) << m;  // lists the valid names

  r.kind = "vvalley";
  r.params = {{"angle_deg", 200}};
  m = errorOf(r);
  EXPECT_NE(m.find("angle_deg=200"), std::string::npos) << m;
  EXPECT_NE(m.find("[10, 170] deg"), std::string::npos) << m;

  r.kind = "sine";
  r.params = {{"amplitude", std::numeric_limits<double>::quiet_NaN()}};
  m = errorOf(r);
  EXPECT_NE(m.find("amplitude=nan"), std::string::npos) << m;

  r.params = {{"period", -0.01}};
  m = errorOf(r);
  EXPECT_NE(m.find("period=-0.01"), std::string::npos) << m;

  r.kind = "grooves";
  r.params = {{"width", 0.01}};  // wider than the default 8 mm period
  m = errorOf(r);
  EXPECT_NE(m.find("width=0.01"), std::string::npos) << m;
  EXPECT_NE(m.find("period=0.008"), std::string::npos) << m;

  r.kind = "dimples";
  r.params = {{"radius", 0.006}};
  m = errorOf(r);
  EXPECT_NE(m.find("radius=0.006"), std::string::npos) << m;

  r.kind = "pebbles";
  r.params = {{"height", 0.003}};
  m = errorOf(r);
  EXPECT_NE(m.find("height=0.003"), std::string::npos) << m;

  r.kind = "tilted";
  r.params = {};
  r.size = 1;
  m = errorOf(r);
  EXPECT_NE(m.find("size=1"), std::string::npos) << m;
  r.size = kMaxTextureSide + 1;
  EXPECT_NE(errorOf(r).find("size="), std::string::npos);

  try {
    generate({"vvalley", 16, {{"period", 0.0}}, 1});
    FAIL() << "no error";
  } catch (const TextureError& e) {
    EXPECT_EQ(e.source(), "generator vvalley");
    EXPECT_EQ(e.value(), "period=0");
  }
}

// The surfaces of the user studies (porcelain, metal, stone, ceramic_tile): what each pattern
// promises, checked where it is known exactly.

// Metal's other patterns (the defaults test covers brushed) keep normals and depth consistent.
TEST(SurfaceGenerators, MetalKnurledAndHammeredNormalsAgreeWithTheirDepth) {
  const int n = 256;
  const double extent = 0.025;
  for (const double pattern : {1.0, 2.0}) {
    const TextureMap m = make("metal", n, {{"extent", extent}, {"pattern", pattern}});
    const Consistency c = checkConsistency(m, extent / n);
    EXPECT_EQ(c.failed, 0) << "pattern " << pattern;
    std::printf("[ metal ] pattern %g: tested %.1f %% of interior texels, mirrored slope caught at %.1f %%\n", pattern,
                100 * double(c.tested) / ((n - 4) * (n - 4)), 100 * double(c.flip_caught) / double(c.tested));
    // The scratches (on every pattern) are a few texels wide here, and skipped like creases.
    EXPECT_GE(double(c.tested), 0.5 * (n - 4) * (n - 4)) << "pattern " << pattern;
    EXPECT_GE(double(c.flip_caught), 0.5 * double(c.tested)) << "pattern " << pattern;
  }
}

// Without undulation the tile is exact: grout texels (within grout/2 of a joint line x or y = k *
// tile) lie grout_depth below the faces, and faces (beyond grout/2 + bevel from every joint) at 0.
TEST(SurfaceGenerators, CeramicTileGroutSitsOnTheJointLines) {
  const int n = 200;
  const double extent = 0.2, tile = 0.05, grout = 0.004, depth = 0.001, bevel = 0.002, d = extent / n;
  const TextureMap m = make("ceramic_tile", n,
                            {{"extent", extent}, {"tile", tile}, {"grout", grout}, {"grout_depth", depth},
                             {"bevel", bevel}, {"undulation", 0.0}});
  EXPECT_NEAR(m.maxDepth(), depth, 1e-9);
  const double q = m.maxDepth() / 65535;
  int grout_texels = 0, face_texels = 0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      auto edge = [&](double c) { return std::fabs(c - std::round(c / tile) * tile); };
      const double ex = edge((i + 0.5) * d), ey = edge(extent - (j + 0.5) * d);
      if (std::min(ex, ey) < grout / 2) {
        EXPECT_NEAR(m.depth(i, j), depth, q) << i << "," << j;
        ++grout_texels;
      } else if (std::min(ex, ey) > grout / 2 + bevel) {
        EXPECT_NEAR(m.depth(i, j), 0.0, q) << i << "," << j;
        EXPECT_LT(angleBetween(m.normal(i, j).cast<double>(), Eigen::Vector3d::UnitZ()), 1e-4);
        ++face_texels;
      }
    }
  }
  // 1 mm texels: 4 joint lines each way (x = 0 = 0.2, 0.05, 0.1, 0.15), 4 texel columns each within
  // grout/2 = 2 mm of one: 16 grout columns and rows; 8 columns per tile are grout or bevel (within
  // 4 mm of a joint), so 4 x 42 columns and rows are face.
  EXPECT_EQ(grout_texels, n * n - (n - 16) * (n - 16));
  EXPECT_EQ(face_texels, 168 * 168);
}

// Porcelain is nearly flat: a few micrometres of undulation, crazing cracks a thin network.
TEST(SurfaceGenerators, PorcelainIsNearlyFlatWithAThinCrackNetwork) {
  const int n = 160;
  const double extent = 0.1;
  const TextureMap plain = make("porcelain", n, {{"extent", extent}, {"craze_depth", 0.0}});
  EXPECT_GT(plain.maxDepth(), 1e-6);
  EXPECT_LT(plain.maxDepth(), 3 * 5e-6);  // |noise| <= ~0.7 per octave, two octaves of 5 and 2.5 um
  const TextureMap crazed = make("porcelain", n, {{"extent", extent}});
  EXPECT_GT(crazed.maxDepth(), 2e-5);
  EXPECT_LT(crazed.maxDepth(), 2e-5 + 3 * 5e-6);
  int cracked = 0;
  double worst_tilt = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      cracked += crazed.depth(i, j) > crazed.maxDepth() - 1e-5;  // within the lower half of a crack
      worst_tilt = std::max(worst_tilt, angleBetween(crazed.normal(i, j).cast<double>(), Eigen::Vector3d::UnitZ()));
    }
  const double share = double(cracked) / (n * n);
  std::printf("[ porcelain ] cracked share %.3f, steepest normal %.2f deg\n", share, worst_tilt * 180 / kPi);
  EXPECT_GT(share, 0.01);
  EXPECT_LT(share, 0.2);
  EXPECT_LT(worst_tilt, 10 * kPi / 180);  // shallow cracks: never steep
}

// Brushed metal is anisotropic: scratches run along x, so slopes across them (y) dominate.
TEST(SurfaceGenerators, BrushedMetalSlopesAcrossTheScratches) {
  const int n = 256;
  const TextureMap m = make("metal", n, {{"extent", 0.05}});
  double sx = 0.0, sy = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d s = slopeOf(m, i, j);
      sx += std::fabs(s.x());
      sy += std::fabs(s.y());
    }
  std::printf("[ metal ] brushed mean |dh/dx| %.2e, mean |dh/dy| %.2e\n", sx / (n * n), sy / (n * n));
  EXPECT_GT(sy, 10 * sx);
  EXPECT_LE(m.maxDepth(), 1.5e-5 + 1e-9);
}

// Knurling repeats with its pitch along x and y; its depth is the groove depth.
TEST(SurfaceGenerators, KnurledMetalRepeatsWithItsPitch) {
  const int n = 200;
  const double extent = 0.05, pitch = 0.005;  // 20 texels per pitch
  const TextureMap m =
      make("metal", n, {{"extent", extent}, {"pattern", 1}, {"knurl_pitch", pitch}, {"scratch_depth", 0.0}});
  EXPECT_NEAR(m.maxDepth(), 0.0005, 0.0005 * 0.05);  // texel centres miss the exact groove bottom
  const double q = m.maxDepth() / 65535;
  for (int j = 0; j + 20 < n; j += 3)
    for (int i = 0; i + 20 < n; i += 5) {
      EXPECT_NEAR(m.depth(i, j), m.depth(i + 20, j), 2 * q) << i << "," << j;
      EXPECT_NEAR(m.depth(i, j), m.depth(i, j + 20), 2 * q) << i << "," << j;
    }
}

// Hammered dents overlap and add up, but stay of the order of dent_depth.
TEST(SurfaceGenerators, HammeredMetalDentsHaveTheirDepth) {
  const TextureMap m = make("metal", 128, {{"extent", 0.05}, {"pattern", 2}, {"scratch_depth", 0.0}});
  EXPECT_GT(m.maxDepth(), 0.5 * 0.0003);
  EXPECT_LT(m.maxDepth(), 4 * 0.0003);
}

// Stone is rough enough for a relief map; its cracks deepen it.
TEST(SurfaceGenerators, StoneHasReliefWorthyDepthAndCracks) {
  const TextureMap rough = make("stone", 256, {{"crack_depth", 0.0}});
  const TextureMap cracked = make("stone", 256);
  EXPECT_GT(rough.maxDepth(), 0.5e-3);
  EXPECT_GT(cracked.maxDepth(), rough.maxDepth() + 0.5e-3);
  EXPECT_LT(cracked.maxDepth(), 6e-3);
}

TEST(SurfaceGenerators, BadParametersNameTheParameter) {
  auto err = [](const std::string& kind, std::map<std::string, double> params) {
    GenerateRequest r;
    r.kind = kind;
    r.size = 16;
    r.params = std::move(params);
    return errorOf(r);
  };
  std::string m = err("metal", {{"pattern", 1.5}});
  EXPECT_NE(m.find("pattern=1.5"), std::string::npos) << m;
  EXPECT_NE(m.find("hammered"), std::string::npos) << m;
  m = err("metal", {{"pattern", 3}});
  EXPECT_NE(m.find("pattern=3"), std::string::npos) << m;
  m = err("stone", {{"octaves", 2.5}});
  EXPECT_NE(m.find("octaves=2.5"), std::string::npos) << m;
  m = err("stone", {{"crack_width", 0.04}});
  EXPECT_NE(m.find("crack_width=0.04"), std::string::npos) << m;
  m = err("porcelain", {{"craze_width", 0.005}});
  EXPECT_NE(m.find("craze_width=0.005"), std::string::npos) << m;
  EXPECT_NE(m.find("craze_cell=0.008"), std::string::npos) << m;
  m = err("ceramic_tile", {{"bevel", 0.03}});
  EXPECT_NE(m.find("bevel=0.03"), std::string::npos) << m;
  m = err("ceramic_tile", {{"grout_depth", -1}});
  EXPECT_NE(m.find("grout_depth=-1"), std::string::npos) << m;
}

// Lattices finer than 1024 points per side hash each point instead of tabulating it
// (textures/generators/noise.hpp); that path is deterministic too.
TEST(SurfaceGenerators, FineLatticesAreHashedDeterministically) {
  const std::map<std::string, double> fine{{"extent", 1.0}, {"craze_cell", 0.0009}, {"craze_width", 0.0002}};
  const TextureMap a = make("porcelain", 32, fine, 5), b = make("porcelain", 32, fine, 5);
  EXPECT_TRUE(identical(a, b));
  EXPECT_GT(a.maxDepth(), 0.0);
}

}  // namespace test_generators
