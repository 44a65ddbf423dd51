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

using namespace thx::tex;

namespace {

constexpr double kPi = 3.14159265358979323846;
const char* const kKinds[] = {"bricks", "vvalley", "grooves", "pebbles", "wood", "sine", "dimples", "tilted", "zigzag"};

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
TEST(Generators, NormalsAgreeWithTheirOwnDepth) {
  struct Case {
    const char* kind;
    double min_tested, min_caught;
  };
  const Case cases[] = {{"bricks", 0.9, 0.1},  {"vvalley", 0.75, 0.99}, {"grooves", 0.85, 0.4},
                        {"pebbles", 0.9, 0.2}, {"wood", 1.0, 0.5},      {"sine", 1.0, 0.9},
                        {"dimples", 0.9, 0.2}, {"tilted", 1.0, 0.99},   {"zigzag", 0.95, 0.3}};
  const int n = 256;
  const double extent = 0.025, texel = extent / n;
  for (const Case& k : cases) {
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
}

TEST(Generators, SameSeedSameMapDifferentSeedDifferentMap) {
  for (const char* kind : kKinds) {
    const TextureMap a = make(kind, 96, {}, 42), b = make(kind, 96, {}, 42), c = make(kind, 96, {}, 43);
    EXPECT_TRUE(identical(a, b)) << kind;
    const std::string k = kind;
    const bool seeded = k == "bricks" || k == "pebbles" || k == "wood";
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
