#include "meshes/textured_ball_mesh.hpp"

#include <array>
#include <cmath>
#include <numbers>

#include "base/error.hpp"

namespace thx::mesh {

namespace {
// atan(t) for |t| <= 1 within three ulp of libm's (2.2e-16), at a third of its cost: libm's
// atan2 took a quarter of a rolling bump-mapped ball's physics step, which reads the chart at every
// texel under the ball (bench_textured_ball). Atan's Taylor series about the nearest knot
// t_k = k / 32, in h = t - t_k with |h| <= 1/64: with t_k = cot(phi), its n-th coefficient is
// (-1)^(n-1) sin^n(phi) sin(n phi) / n, so ten terms leave under 1e-20. No division, and a short
// chain (Estrin's scheme), since each read waits on its angles.
constexpr int kKnotsPerUnit = 32;
constexpr int kTerms = 10;
using KnotSeries = std::array<double, kTerms + 1>;
const std::array<KnotSeries, 2 * kKnotsPerUnit + 1> kKnotSeries = [] {
  std::array<KnotSeries, 2 * kKnotsPerUnit + 1> series{};
  for (int k = -kKnotsPerUnit; k <= kKnotsPerUnit; ++k) {
    const double tk = double(k) / kKnotsPerUnit, phi = 0.5 * std::numbers::pi - std::atan(tk);
    KnotSeries& c = series[std::size_t(k + kKnotsPerUnit)];
    c[0] = std::atan(tk);
    for (int n = 1; n <= kTerms; ++n)
      c[std::size_t(n)] = (n % 2 ? 1.0 : -1.0) * std::pow(std::sin(phi), n) * std::sin(n * phi) / n;
  }
  return series;
}();

double angleOfSlope(double t) {
  if (!(std::fabs(t) <= 1.0)) return std::atan(t);  // not from a unit direction's face (NaN)
  const int index = int(t * kKnotsPerUnit + (kKnotsPerUnit + 0.5));  // nearest knot, from 0
  const double h = t - double(index - kKnotsPerUnit) / kKnotsPerUnit;
  const KnotSeries& c = kKnotSeries[std::size_t(index)];
  const double h2 = h * h, h4 = h2 * h2, h8 = h4 * h4;
  const double low = (c[0] + h * c[1]) + h2 * (c[2] + h * c[3]);
  const double mid = (c[4] + h * c[5]) + h2 * (c[6] + h * c[7]);
  const double high = (c[8] + h * c[9]) + h2 * c[10];
  return low + h4 * mid + h8 * high;
}
}  // namespace

BallChartPoint ballChartUvAtUnit(const Eigen::Vector3d& w, double radius_m) {
  BallChartPoint c;
  c.axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::fabs(w[k]) > std::fabs(w[c.axis])) c.axis = k;
  const int a = c.axis, b = (a + 1) % 3, d = (a + 2) % 3;
  c.sign = w[a] < 0.0 ? -1.0 : 1.0;
  const double wa = std::fabs(w[a]);
  // |w_b| and |w_d| are at most |w_a|, which is at least 1/sqrt(3).
  const double per_wa = 1.0 / wa;
  c.uv_m = radius_m * Eigen::Vector2d(angleOfSlope(w[b] * per_wa), angleOfSlope(w[d] * per_wa));
  return c;
}

BallChartPoint ballChartAt(const Eigen::Vector3d& direction, double radius_m) {
  const Eigen::Vector3d w = direction.normalized();
  BallChartPoint c = ballChartUvAtUnit(w, radius_m);
  const int a = c.axis, b = (a + 1) % 3, d = (a + 2) % 3;
  const double wa = std::fabs(w[a]);
  // u = r atan(P_b / |P_a|) for P = r w: its gradient in space, tangent to the sphere already
  // (u does not change along P), is (|w_a| e_b - sign w_b e_a) / (w_a^2 + w_b^2) on the sphere.
  const double ab = w[a] * w[a] + w[b] * w[b], ad = w[a] * w[a] + w[d] * w[d];
  c.du = Eigen::Vector3d::Zero();
  c.du[b] = wa / ab;
  c.du[a] = -c.sign * w[b] / ab;
  c.dv = Eigen::Vector3d::Zero();
  c.dv[d] = wa / ad;
  c.dv[a] = -c.sign * w[d] / ad;
  return c;
}

double ballFaceArc(double radius_m) { return 0.5 * std::numbers::pi * radius_m; }

TexturedMesh texturedBallMesh(double radius_m, double tile_m, int cells) {
  if (!std::isfinite(radius_m) || radius_m <= 0.0 || !std::isfinite(tile_m) || tile_m <= 0.0)
    throw Error(Error::Kind::Config, "textured ball: radius and texture tile must be positive and finite");
  if (cells < 1 || cells > 256) throw Error(Error::Kind::Config, "textured ball: cells per face edge must be in [1, 256]");
  TexturedMesh ball;
  ball.source = "textured ball";
  const double quarter = 0.25 * std::numbers::pi;
  // tan of the k-th angle, exactly +-1 on the faces' edges: a point two faces share must get the
  // same position bit for bit from both, or the frames see two open edges (normals 3.4 degrees off).
  const auto slope = [&](int k) {
    return k == 0 ? -1.0 : k == cells ? 1.0 : std::tan(-quarter + 2.0 * quarter * double(k) / double(cells));
  };
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, d = (a + 2) % 3;
    for (const double sign : {1.0, -1.0}) {
      const auto first = std::uint32_t(ball.positions.size());
      for (int j = 0; j <= cells; ++j) {
        for (int i = 0; i <= cells; ++i) {
          const double alpha = -quarter + 2.0 * quarter * double(i) / double(cells);
          const double beta = -quarter + 2.0 * quarter * double(j) / double(cells);
          Eigen::Vector3d w = Eigen::Vector3d::Zero();
          w[a] = sign;
          w[b] = slope(i);
          w[d] = slope(j);
          ball.positions.push_back(radius_m * w.normalized());
          ball.uvs.emplace_back(radius_m * alpha / tile_m, radius_m * beta / tile_m);
        }
      }
      // Counter-clockwise seen from outside: e_b x e_d = e_a, so (i, j), (i+1, j), (i+1, j+1)
      // winds outwards on the positive face and must be reversed on the negative one.
      const auto at = [&](int i, int j) { return first + std::uint32_t(j * (cells + 1) + i); };
      for (int j = 0; j < cells; ++j) {
        for (int i = 0; i < cells; ++i) {
          const std::uint32_t p00 = at(i, j), p10 = at(i + 1, j), p11 = at(i + 1, j + 1), p01 = at(i, j + 1);
          if (sign > 0.0) {
            ball.triangles.push_back({p00, p10, p11});
            ball.triangles.push_back({p00, p11, p01});
          } else {
            ball.triangles.push_back({p00, p11, p10});
            ball.triangles.push_back({p00, p01, p11});
          }
        }
      }
    }
  }
  buildVertexFrames(ball);
  return ball;
}

}  // namespace thx::mesh
