// Gradient-domain Gaussian smoothing (textures/smoothing.hpp).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "textures/generators.hpp"
#include "textures/smoothing.hpp"
#include "textures/texture_error.hpp"

namespace test_smoothing {

using namespace thx::tex;

namespace {

constexpr double kPi = 3.14159265358979323846;

TextureMap make(const std::string& kind, int size, std::map<std::string, double> params = {}) {
  return generate({kind, size, std::move(params), 1});
}

TextureMap smooth(const TextureMap& m, double sigma, Address address = Address::Wrap) {
  SmoothOptions o;
  o.sigma_texels = sigma;
  o.address = address;
  return smoothTexture(m, o);
}

double angleBetween(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  const Eigen::Vector3d x = a.cast<double>(), y = b.cast<double>();
  return std::atan2(x.cross(y).norm(), x.dot(y));
}

Eigen::Vector2d slopeOf(const TextureMap& m, int i, int j) {
  const Eigen::Vector3d n = m.normal(i, j).cast<double>();
  return {-n.x() / n.z(), -n.y() / n.z()};
}

// Per texel: central difference of the depth minus the slope of the normal (dh/dx, dh/dy),
// differencing across the border periodically (the rule Address::Wrap smoothing uses).
std::vector<Eigen::Vector2d> mismatch(const TextureMap& m, double texel_m) {
  const int w = m.width(), h = m.height();
  std::vector<Eigen::Vector2d> out;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const int l = (i + w - 1) % w, r = (i + 1) % w, up = (j + h - 1) % h, dn = (j + 1) % h;
      const Eigen::Vector2d fd(-(double(m.depth(r, j)) - m.depth(l, j)) / (2 * texel_m),
                               -(double(m.depth(i, up)) - m.depth(i, dn)) / (2 * texel_m));
      out.push_back(fd - slopeOf(m, i, j));
    }
  }
  return out;
}

double maxAbs(const std::vector<Eigen::Vector2d>& field) {
  double worst = 0.0;
  for (const Eigen::Vector2d& v : field) worst = std::max(worst, v.cwiseAbs().maxCoeff());
  return worst;
}

// Periodic separable Gaussian (sampled, normalised, radius ceil(4 sigma)): the kernel
// smoothing.hpp documents, written out independently of OpenCV.
std::vector<Eigen::Vector2d> periodicBlur(const std::vector<Eigen::Vector2d>& field, int w, int h, double sigma) {
  const int r = int(std::ceil(4 * sigma));
  std::vector<double> k;
  double sum = 0.0;
  for (int d = -r; d <= r; ++d) sum += k.emplace_back(std::exp(-d * d / (2 * sigma * sigma)));
  for (double& x : k) x /= sum;
  std::vector<Eigen::Vector2d> rows(field.size(), Eigen::Vector2d::Zero()), out(field.size(), Eigen::Vector2d::Zero());
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      for (int d = -r; d <= r; ++d) rows[std::size_t(j * w + i)] += k[std::size_t(d + r)] * field[std::size_t(j * w + ((i + d) % w + w) % w)];
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      for (int d = -r; d <= r; ++d) out[std::size_t(j * w + i)] += k[std::size_t(d + r)] * rows[std::size_t(((j + d) % h + h) % h * w + i)];
  return out;
}

TextureMap rolled(const TextureMap& m, int di, int dj) {
  TextureMap out(m.width(), m.height(), m.representation(), m.maxDepth());
  for (int j = 0; j < m.height(); ++j) {
    for (int i = 0; i < m.width(); ++i) {
      const int si = (i - di + m.width()) % m.width(), sj = (j - dj + m.height()) % m.height();
      out.setNormal(i, j, m.normal(si, sj));
      out.setDepthCode(i, j, m.depthCode(si, sj));
    }
  }
  return out;
}

}  // namespace

TEST(Smoothing, ZeroSigmaIsTheIdentity) {
  const TextureMap m = make("pebbles", 64);
  const TextureMap s = smooth(m, 0.0);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      EXPECT_EQ(s.depthCode(i, j), m.depthCode(i, j));
      EXPECT_EQ(s.normal(i, j), m.normal(i, j));
    }
}

// sigma = 0.05 texel: the neighbours' weight is exp(-200), so only re-quantisation remains
// (normals: a few snorm16 steps; depth: exact codes).
TEST(Smoothing, TinySigmaIsTheIdentityWithinQuantisation) {
  const TextureMap m = make("bricks", 64);
  const TextureMap s = smooth(m, 0.05);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      EXPECT_EQ(s.depthCode(i, j), m.depthCode(i, j));
      EXPECT_LT(angleBetween(s.normal(i, j), m.normal(i, j)), 1e-4);
    }
}

// A plane's slope is the same everywhere, so its normals survive any blur and any border rule;
// its depth is unchanged away from the clamped border (replicated edges flatten the ramp there).
TEST(Smoothing, APlaneIsUnchanged) {
  const TextureMap m = make("tilted", 96, {{"angle_deg", 25}, {"direction_deg", 40}});
  for (Address address : {Address::Clamp, Address::Wrap}) {
    const TextureMap s = smooth(m, 3.0, address);
    for (int j = 0; j < 96; ++j)
      for (int i = 0; i < 96; ++i) EXPECT_LT(angleBetween(s.normal(i, j), m.normal(i, j)), 1e-4);
    if (address == Address::Clamp) {
      for (int j = 12; j < 84; ++j)
        for (int i = 12; i < 84; ++i) EXPECT_NEAR(int(s.depthCode(i, j)), int(m.depthCode(i, j)), 1);
    }
  }
}

// Blurring is linear and commutes with (periodic) differencing, so the smoothed map's mismatch
// between depth differences and normal slopes is exactly the input's mismatch, blurred: texel by
// texel, up to re-quantisation (depth codes: q / d for each map; snorm16 normals: 3e-4 (1 + s^2)).
// Hence it is never worse than the input's worst. Bricks, dimples and V-valleys have creases,
// where the input mismatch is large, so this checks the hard case, not just smooth surfaces.
TEST(Smoothing, ReliefNormalsStayConsistentWithDepth) {
  const int n = 128;
  const double texel = 0.04 / n, sigma = 2.0;
  for (const char* kind : {"bricks", "dimples", "vvalley"}) {
    const TextureMap m = make(kind, n, {{"extent", 0.04}});
    const TextureMap s = smooth(m, sigma);
    const std::vector<Eigen::Vector2d> before = mismatch(m, texel), after = mismatch(s, texel);
    const std::vector<Eigen::Vector2d> expected = periodicBlur(before, n, n, sigma);
    const double q = 2 * m.maxDepth() / 65535 / texel;
    double worst = 0.0;
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const std::size_t k = std::size_t(j * n + i);
        const double tol = q + 3e-4 * (1 + slopeOf(s, i, j).squaredNorm());
        const double err = (after[k] - expected[k]).cwiseAbs().maxCoeff();
        worst = std::max(worst, err / tol);
        if (err > tol) ADD_FAILURE() << kind << " texel (" << i << ", " << j << "): " << err << " > " << tol;
        if (err > tol) break;
      }
    }
    std::printf("[ smoothing ] %-8s sigma %.1f: max |mismatch| %.3f before, %.3f after; after = blurred before "
                "within %.2f x tolerance\n",
                kind, sigma, maxAbs(before), maxAbs(after), worst);
    EXPECT_GT(maxAbs(before), 0.05) << kind << ": creases make the input disagree somewhere";
    EXPECT_LE(maxAbs(after), maxAbs(before));
  }
}

// On a smooth surface the smoothed map is itself a consistent relief: the normals match its depth
// everywhere, and the sinusoid's amplitude drops by the Gaussian's transfer function
// exp(-(k sigma)^2 / 2) per axis.
TEST(Smoothing, SmoothedSinusoidIsTheBlurredSinusoid) {
  const int n = 160;  // period 0.01 m over 0.08 m: 20 texels per period, 8 periods (tiles)
  const TextureMap m = make("sine", n, {{"extent", 0.08}, {"amplitude", 0.0005}, {"period", 0.01}});
  const TextureMap s = smooth(m, 3.0);
  const double texel = 0.08 / n;
  // Central differences of a sinusoid with 20 texels per period under-read the slope by
  // (k d)^2 / 6 = 1.6 % (k d = 2 pi / 20); the slope here is at most 0.31 * 0.41.
  EXPECT_LT(maxAbs(mismatch(s, texel)), 0.017 * 0.31 * 0.41 + s.maxDepth() / 65535 / texel + 1e-3);
  const double kd_sigma = 2 * kPi / 20 * 3.0;
  const double gain = std::exp(-kd_sigma * kd_sigma / 2) * std::exp(-kd_sigma * kd_sigma / 2);
  // Same texel centres before and after, so the sampled depth ranges scale exactly by the gain.
  auto range = [](const TextureMap& t) {
    int lo = 65535, hi = 0;
    for (int j = 0; j < t.height(); ++j)
      for (int i = 0; i < t.width(); ++i) {
        lo = std::min<int>(lo, t.depthCode(i, j));
        hi = std::max<int>(hi, t.depthCode(i, j));
      }
    return (hi - lo) * t.maxDepth() / 65535;
  };
  EXPECT_NEAR(range(s) / range(m), gain, 0.005 * gain);
}

// Wrap mode treats the map as a torus: smoothing commutes with a circular shift, so nothing marks
// where the border was. Wood does not tile, so its border is a real seam that wrap must carry
// through, and clamp must not.
TEST(Smoothing, WrapIsSeamless) {
  const TextureMap m = make("wood", 64, {{"extent", 0.05}});
  const int di = 23, dj = 41;
  const TextureMap a = rolled(smooth(m, 2.5), di, dj), b = smooth(rolled(m, di, dj), 2.5);
  double worst = 0.0;
  int worst_code = 0;
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      worst = std::max(worst, angleBetween(a.normal(i, j), b.normal(i, j)));
      worst_code = std::max(worst_code, std::abs(int(a.depthCode(i, j)) - int(b.depthCode(i, j))));
    }
  EXPECT_LT(worst, 1e-4);
  EXPECT_LE(worst_code, 1);

  const TextureMap c = rolled(smooth(m, 2.5, Address::Clamp), di, dj), d = smooth(rolled(m, di, dj), 2.5, Address::Clamp);
  int clamp_code = 0;
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) clamp_code = std::max(clamp_code, std::abs(int(c.depthCode(i, j)) - int(d.depthCode(i, j))));
  EXPECT_GT(clamp_code, 100) << "clamp should see the seam the shift moved";
}

TEST(Smoothing, NormalMapsStayNormalMaps) {
  TextureMap m(8, 8, Representation::Normal);
  m.setNormal(3, 3, Eigen::Vector3f(0.5f, 0.0f, 1.0f));
  const TextureMap s = smooth(m, 1.0);
  EXPECT_FALSE(s.isRelief());
  EXPECT_GT(s.normal(4, 3).x(), 0.0f);  // the bump spread to its neighbour
  EXPECT_LT(s.normal(3, 3).x(), m.normal(3, 3).x());
}

// A grazing normal encodes a huge slope; clamping it to max_slope keeps the neighbours sane.
TEST(Smoothing, GrazingNormalsAreBounded) {
  TextureMap m(9, 9, Representation::Normal);
  m.setNormal(4, 4, Eigen::Vector3f(1.0f, 0.0f, 1e-4f));  // slope ~ -1e4 before the bound
  const TextureMap s = smooth(m, 1.0);
  const Eigen::Vector3f n = s.normal(5, 4);
  EXPECT_GT(n.z(), 0.1f);  // 50 * weight(1 texel) ~ 12: a steep but finite slope
}

TEST(Smoothing, BadSigmaIsRefused) {
  const TextureMap m = make("sine", 16);
  for (double sigma : {-1.0, std::numeric_limits<double>::quiet_NaN(), 1e6}) {
    try {
      smooth(m, sigma);
      FAIL() << sigma;
    } catch (const TextureError& e) {
      EXPECT_NE(std::string(e.what()).find("sigma="), std::string::npos) << e.what();
    }
  }
}

}  // namespace test_smoothing
