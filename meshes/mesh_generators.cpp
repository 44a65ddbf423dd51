#include "meshes/mesh_generators.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "base/error.hpp"

namespace thx::mesh {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw Error(Error::Kind::Config, what);
}

// Whole tiles around a closed loop of `length` metres (at least one).
double wholeTiles(double length_m, double tile_m) { return std::max(1.0, std::round(length_m / tile_m)); }

// A (cols + 1) x (rows + 1) grid of vertices, quads (i, j) -> (i+1, j+1) split along the same
// diagonal everywhere, wound so that d(position)/du x d(position)/dv is the outward side.
// Triangles with two corners at one position (a pole, a point on a lathe's axis) are left out.
void addGrid(TexturedMesh& m, int cols, int rows, const std::function<Eigen::Vector3d(int, int)>& position,
             const std::function<Eigen::Vector2d(int, int)>& uv) {
  const std::uint32_t base = std::uint32_t(m.positions.size());
  for (int j = 0; j <= rows; ++j) {
    for (int i = 0; i <= cols; ++i) {
      m.positions.push_back(position(i, j));
      m.uvs.push_back(uv(i, j));
    }
  }
  auto at = [&](int i, int j) { return base + std::uint32_t(j * (cols + 1) + i); };
  auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const auto& p = m.positions;
    if (p[a] == p[b] || p[b] == p[c] || p[a] == p[c]) return;
    m.triangles.push_back({a, b, c});
  };
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < cols; ++i) {
      add(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      add(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
}

GeneratedMesh finish(TexturedMesh&& m, Eigen::Vector2d tile_used) {
  buildVertexFrames(m);
  return {std::move(m), tile_used};
}

void checkCounts(const char* what, int a, const char* a_name, int b, const char* b_name, double tile_m) {
  require(a >= 3 && a <= 4096 && b >= 1 && b <= 4096,
          std::string(what) + ": " + a_name + " " + std::to_string(a) + " and " + b_name + " " + std::to_string(b) +
              "; expected 3..4096 and 1..4096");
  require(std::isfinite(tile_m) && tile_m > 0.0, std::string(what) + ": tile " + std::to_string(tile_m) + " m; expected > 0");
}

}  // namespace

GeneratedMesh sphere(double radius_m, int segments, int rings, double tile_m) {
  checkCounts("sphere", segments, "segments", rings, "rings", tile_m);
  require(std::isfinite(radius_m) && radius_m > 0.0, "sphere: radius must be > 0");
  require(rings >= 2, "sphere: rings " + std::to_string(rings) + "; expected >= 2");
  const double nu = wholeTiles(2 * M_PI * radius_m, tile_m), nv = std::max(1.0, std::round(M_PI * radius_m / tile_m));
  TexturedMesh m;
  m.source = "sphere(r=" + std::to_string(radius_m) + " m)";
  addGrid(
      m, segments, rings,
      [&](int i, int j) -> Eigen::Vector3d {
        // i % segments: the seam's last column repeats the first bit for bit, so the mesh is closed.
        const double phi = 2 * M_PI * (i % segments) / segments, theta = M_PI * j / rings;  // from the south pole
        if (j == 0) return {0.0, 0.0, -radius_m};
        if (j == rings) return {0.0, 0.0, radius_m};
        const double s = std::sin(theta);
        return {radius_m * s * std::cos(phi), radius_m * s * std::sin(phi), -radius_m * std::cos(theta)};
      },
      [&](int i, int j) { return Eigen::Vector2d(nu * i / segments, nv * j / rings); });
  return finish(std::move(m), {2 * M_PI * radius_m / nu, M_PI * radius_m / nv});
}

GeneratedMesh cylinder(double radius_m, double height_m, int segments, int rows, double tile_m, bool inward) {
  checkCounts("cylinder", segments, "segments", rows, "rows", tile_m);
  require(std::isfinite(radius_m) && radius_m > 0.0 && std::isfinite(height_m) && height_m > 0.0,
          "cylinder: radius and height must be > 0");
  const double nu = wholeTiles(2 * M_PI * radius_m, tile_m);
  TexturedMesh m;
  m.source = std::string(inward ? "pipe" : "cylinder") + "(r=" + std::to_string(radius_m) + " m)";
  // Inside a pipe u runs the other way round, so the chart keeps its handedness (+1) seen from
  // the side the surface faces.
  const double sense = inward ? -1.0 : 1.0;
  addGrid(
      m, segments, rows,
      [&](int i, int j) -> Eigen::Vector3d {
        const double phi = sense * 2 * M_PI * (i % segments) / segments;
        return {radius_m * std::cos(phi), radius_m * std::sin(phi), height_m * j / rows};
      },
      [&](int i, int j) { return Eigen::Vector2d(nu * i / segments, height_m * j / rows / tile_m); });
  return finish(std::move(m), {2 * M_PI * radius_m / nu, tile_m});
}

GeneratedMesh torus(double major_radius_m, double minor_radius_m, int segments, int rings, double tile_m) {
  checkCounts("torus", segments, "segments", rings, "rings", tile_m);
  require(std::isfinite(major_radius_m) && std::isfinite(minor_radius_m) && minor_radius_m > 0.0 &&
              major_radius_m > minor_radius_m,
          "torus: expected major radius > minor radius > 0");
  require(rings >= 3, "torus: rings " + std::to_string(rings) + "; expected >= 3");
  const double nu = wholeTiles(2 * M_PI * major_radius_m, tile_m), nv = wholeTiles(2 * M_PI * minor_radius_m, tile_m);
  TexturedMesh m;
  m.source = "torus(R=" + std::to_string(major_radius_m) + " m, r=" + std::to_string(minor_radius_m) + " m)";
  addGrid(
      m, segments, rings,
      [&](int i, int j) -> Eigen::Vector3d {
        // The last column and row repeat the first exactly, so the seams close bit for bit.
        const double phi = 2 * M_PI * (i % segments) / segments, theta = 2 * M_PI * (j % rings) / rings;
        const double rho = major_radius_m + minor_radius_m * std::cos(theta);
        return {rho * std::cos(phi), rho * std::sin(phi), minor_radius_m * std::sin(theta)};
      },
      [&](int i, int j) { return Eigen::Vector2d(nu * i / segments, nv * j / rings); });
  return finish(std::move(m), {2 * M_PI * major_radius_m / nu, 2 * M_PI * minor_radius_m / nv});
}

GeneratedMesh box(const Eigen::Vector3d& size_m, double cell_m, double tile_m, bool inward) {
  require(size_m.allFinite() && size_m.minCoeff() > 0.0, "box: every side must be > 0");
  require(std::isfinite(cell_m) && cell_m > 0.0 && std::isfinite(tile_m) && tile_m > 0.0, "box: cell and tile must be > 0");
  std::array<int, 3> cells{};
  for (int a = 0; a < 3; ++a) {
    const double n = std::ceil(size_m[a] / cell_m - 1e-9);
    require(n <= 4096, "box: " + std::to_string(n) + " cells along a side; expected at most 4096 (a larger cell)");
    cells[std::size_t(a)] = std::max(1, int(n));
  }
  TexturedMesh m;
  m.source = std::string(inward ? "room" : "box") + "(" + std::to_string(size_m.x()) + " x " +
             std::to_string(size_m.y()) + " x " + std::to_string(size_m.z()) + " m)";
  // Coordinate k of the grid along axis a: the same expression on every face, so the faces' edge
  // vertices coincide bit for bit and the box is closed.
  auto coord = [&](int a, int k) { return size_m[a] * (double(k) / cells[std::size_t(a)] - 0.5); };
  for (int axis = 0; axis < 3; ++axis) {
    for (int side : {-1, 1}) {
      // (ua, va): the face's u and v axes with ua x va along the outward normal (side * axis),
      // swapped inside a room so the surface faces the inside with handedness +1.
      int ua = (axis + 1) % 3, va = (axis + 2) % 3;
      if ((side < 0) != inward) std::swap(ua, va);
      addGrid(
          m, cells[std::size_t(ua)], cells[std::size_t(va)],
          [&](int i, int j) -> Eigen::Vector3d {
            Eigen::Vector3d p;
            p[axis] = side * size_m[axis] / 2;
            p[ua] = coord(ua, i);
            p[va] = coord(va, j);
            return p;
          },
          [&](int i, int j) {
            return Eigen::Vector2d((coord(ua, i) + size_m[ua] / 2) / tile_m, (coord(va, j) + size_m[va] / 2) / tile_m);
          });
    }
  }
  return finish(std::move(m), {tile_m, tile_m});
}

GeneratedMesh lathe(const std::vector<Eigen::Vector2d>& profile, int segments, double tile_m) {
  const int n = int(profile.size());
  checkCounts("lathe", segments, "segments", n - 1, "profile segments", tile_m);
  double r_max = 0.0;
  std::vector<double> arc(std::size_t(n), 0.0);
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d& q = profile[std::size_t(k)];
    require(q.allFinite() && q.x() >= 0.0,
            "lathe: profile point " + std::to_string(k) + " (r " + std::to_string(q.x()) + ", z " + std::to_string(q.y()) +
                "); expected finite with r >= 0");
    r_max = std::max(r_max, q.x());
    if (k > 0) {
      const double step = (q - profile[std::size_t(k - 1)]).norm();
      require(step > 0.0, "lathe: profile points " + std::to_string(k - 1) + " and " + std::to_string(k) + " coincide");
      arc[std::size_t(k)] = arc[std::size_t(k - 1)] + step;
    }
  }
  require(r_max > 0.0, "lathe: every profile point lies on the axis");
  const double nu = wholeTiles(2 * M_PI * r_max, tile_m);
  TexturedMesh m;
  m.source = "lathe(" + std::to_string(n) + " profile points)";
  addGrid(
      m, segments, n - 1,
      [&](int i, int j) -> Eigen::Vector3d {
        const Eigen::Vector2d& q = profile[std::size_t(j)];
        if (q.x() == 0.0) return {0.0, 0.0, q.y()};
        const double phi = 2 * M_PI * (i % segments) / segments;
        return {q.x() * std::cos(phi), q.x() * std::sin(phi), q.y()};
      },
      [&](int i, int j) { return Eigen::Vector2d(nu * i / segments, arc[std::size_t(j)] / tile_m); });
  return finish(std::move(m), {2 * M_PI * r_max / nu, tile_m});
}

namespace {
// Appends `samples` points of curve(s), s in (0, 1] (the start is the previous point).
void appendCurve(std::vector<Eigen::Vector2d>& out, int samples, const std::function<Eigen::Vector2d(double)>& curve) {
  for (int k = 1; k <= samples; ++k) out.push_back(curve(double(k) / samples));
}
}  // namespace

std::vector<Eigen::Vector2d> bowlProfile(double radius_m, double height_m, double wall_m, int samples) {
  require(std::isfinite(radius_m) && std::isfinite(height_m) && std::isfinite(wall_m) && wall_m > 0.0 &&
              radius_m > 2 * wall_m && height_m > 2 * wall_m,
          "bowl: expected radius and height more than twice the wall, wall > 0");
  require(samples >= 4 && samples <= 4096, "bowl: samples " + std::to_string(samples) + "; expected 4..4096");
  std::vector<Eigen::Vector2d> p{{0.0, 0.0}};
  // Outside: a quarter ellipse from the bottom centre up to the rim; over the rim on a half
  // circle of the wall's diameter; inside: the same ellipse shrunk by the wall, down to the axis.
  appendCurve(p, samples, [&](double s) {
    const double t = s * M_PI / 2;
    return Eigen::Vector2d(radius_m * std::sin(t), height_m * (1 - std::cos(t)));
  });
  const int rim = std::max(4, samples / 4);
  appendCurve(p, rim, [&](double s) {
    const double a = s * M_PI;
    return Eigen::Vector2d(radius_m - wall_m / 2 + wall_m / 2 * std::cos(a), height_m + wall_m / 2 * std::sin(a));
  });
  appendCurve(p, samples, [&](double s) {
    const double t = (1 - s) * M_PI / 2;
    const double r = (radius_m - wall_m) * std::sin(t);
    return Eigen::Vector2d(s == 1.0 ? 0.0 : r, wall_m + (height_m - wall_m) * (1 - std::cos(t)));
  });
  return p;
}

std::vector<Eigen::Vector2d> vaseProfile(double height_m, double max_radius_m, double wall_m, int samples) {
  require(std::isfinite(height_m) && std::isfinite(max_radius_m) && std::isfinite(wall_m) && wall_m > 0.0 &&
              max_radius_m > 4 * wall_m && height_m > 4 * wall_m,
          "vase: expected height and radius more than four walls, wall > 0");
  require(samples >= 4 && samples <= 4096, "vase: samples " + std::to_string(samples) + "; expected 4..4096");
  // Outer radius over s = z / height: a belly at s = 0.41 (the full radius), a neck of 0.45 of it
  // at the top, flaring slightly into the lip.
  auto outer = [&](double s) {
    return max_radius_m * (0.45 + 0.55 * std::sin(M_PI * (0.15 + 0.85 * s)) + 0.15 * std::pow(s, 6));
  };
  std::vector<Eigen::Vector2d> p{{0.0, 0.0}};
  const int flat = std::max(2, samples / 8);
  appendCurve(p, flat, [&](double s) { return Eigen::Vector2d(outer(0.0) * s, 0.0); });
  appendCurve(p, samples, [&](double s) { return Eigen::Vector2d(outer(s), height_m * s); });
  const double top = outer(1.0);
  appendCurve(p, std::max(4, samples / 4), [&](double s) {
    const double a = s * M_PI;
    return Eigen::Vector2d(top - wall_m / 2 + wall_m / 2 * std::cos(a), height_m + wall_m / 2 * std::sin(a));
  });
  const double s_floor = wall_m / height_m;
  appendCurve(p, samples, [&](double s) {
    const double z = height_m - (height_m - wall_m) * s;
    return Eigen::Vector2d(outer(std::max(s_floor, z / height_m)) - wall_m, z);
  });
  const double inner_floor = outer(s_floor) - wall_m;
  appendCurve(p, flat, [&](double s) { return Eigen::Vector2d(s == 1.0 ? 0.0 : inner_floor * (1 - s), wall_m); });
  return p;
}

}  // namespace thx::mesh
