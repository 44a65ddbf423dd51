// Per-vertex tangent frames (meshes/textured_mesh.hpp): smooth where the surface is, hard at a
// box's edges, continuous across a wrapped texture seam, split at mirrored charts, and the
// interpolated frame continuous across every edge.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "base/error.hpp"
#include "meshes/mesh_generators.hpp"
#include "meshes/textured_mesh.hpp"

namespace test_vertex_frames {

using namespace thx::mesh;

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

TEST(VertexFrames, SphereFramesAreRadialOrthonormalAndRightHanded) {
  const TexturedMesh m = sphere(0.05, 32, 16, 0.01).mesh;
  ASSERT_TRUE(m.hasFrames());
  double worst = 0.0;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    worst = std::max(worst, angleDeg(m.normals[v], m.positions[v].normalized()));
    EXPECT_NEAR(m.normals[v].norm(), 1.0, 1e-12);
    EXPECT_NEAR(m.tangents[v].norm(), 1.0, 1e-12);
    EXPECT_NEAR(m.normals[v].dot(m.tangents[v]), 0.0, 1e-12);
    EXPECT_EQ(m.handedness[v], 1.0f);
  }
  // The diagonal of each quad tilts a ring's angle-weighted mean a little off the radius.
  EXPECT_LT(worst, 1.0);
}

TEST(VertexFrames, WrappedSeamKeepsOneFrame) {
  // Cylinder: the seam's two columns of vertices (u = 0 and u = whole tiles) hold the same frame,
  // so nothing felt or seen changes across the seam.
  const TexturedMesh m = cylinder(0.03, 0.05, 24, 4, 0.01).mesh;
  std::map<std::array<double, 3>, std::vector<std::size_t>> at;
  for (std::size_t v = 0; v < m.positions.size(); ++v) at[{m.positions[v].x(), m.positions[v].y(), m.positions[v].z()}].push_back(v);
  int seam = 0;
  for (const auto& [p, vs] : at) {
    if (vs.size() < 2) continue;
    ++seam;
    for (std::size_t k = 1; k < vs.size(); ++k) {
      EXPECT_EQ(m.normals[vs[0]], m.normals[vs[k]]);
      EXPECT_EQ(m.tangents[vs[0]], m.tangents[vs[k]]);
      const double du = m.uvs[vs[k]].x() - m.uvs[vs[0]].x();
      EXPECT_NEAR(du, std::round(du), 1e-12);
      EXPECT_NE(du, 0.0);
    }
  }
  EXPECT_EQ(seam, 5);  // one seam vertex per row of vertices
}

TEST(VertexFrames, BoxKeepsItsEdgesHard) {
  const TexturedMesh m = box({0.04, 0.03, 0.02}, 0.01, 0.02).mesh;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    Eigen::Vector3d n, tan;
    double h = 0.0;
    triangleFrame(m, std::uint32_t(t), n, tan, h);
    EXPECT_EQ(h, 1.0);
    for (std::uint32_t v : m.triangles[t]) {
      EXPECT_LT(angleDeg(m.normals[v], n), 1e-9) << "triangle " << t;
      EXPECT_LT(angleDeg(m.tangents[v], tan), 1e-9) << "triangle " << t;
    }
  }
}

// faceNormal computes the normal alone (the physics asks it of every triangle in reach each step):
// it must be triangleFrame's, to the bit, on curved, flat and inward-facing meshes.
TEST(VertexFrames, AFacesNormalIsItsFramesNormalToTheBit) {
  for (const TexturedMesh& m : {sphere(0.05, 32, 16, 0.01).mesh, box({0.04, 0.03, 0.02}, 0.01, 0.02).mesh,
                                box({0.04, 0.04, 0.04}, 0.02, 0.02, true).mesh}) {
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      Eigen::Vector3d n, tan;
      double h = 0.0;
      triangleFrame(m, std::uint32_t(t), n, tan, h);
      EXPECT_EQ(faceNormal(m, std::uint32_t(t)), n) << "triangle " << t;
    }
  }
}

TEST(VertexFrames, RoomFacesInward) {
  const TexturedMesh m = box({0.04, 0.04, 0.04}, 0.02, 0.02, true).mesh;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    EXPECT_LT(m.normals[v].dot(m.positions[v]), 0.0);  // towards the centre
    EXPECT_EQ(m.handedness[v], 1.0f);
  }
}

// Two triangles of a unit quad in z = 0 with the given corner uvs (corners (0,0) (1,0) (1,1) (0,1)).
TexturedMesh quad(std::array<Eigen::Vector2d, 4> uv) {
  TexturedMesh m;
  m.source = "quad";
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.uvs.assign(uv.begin(), uv.end());
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

TEST(VertexFrames, MirroredChartIsLeftHandedAndItsBitangentFollowsV) {
  // u decreases along +x: the texture is mirrored; its +u direction is -x, +v is +y.
  TexturedMesh m = quad({Eigen::Vector2d(1, 0), {0, 0}, {0, 1}, {1, 1}});
  buildVertexFrames(m);
  for (std::size_t v = 0; v < m.positions.size(); ++v) EXPECT_EQ(m.handedness[v], -1.0f);
  const SurfaceFrame f = frameAt(m, 0, {0.2, 0.3, 0.5});
  EXPECT_LT((f.tangent - Eigen::Vector3d(-1, 0, 0)).norm(), 1e-12);
  EXPECT_LT((f.bitangent - Eigen::Vector3d(0, 1, 0)).norm(), 1e-12);
  EXPECT_LT((f.normal - Eigen::Vector3d(0, 0, 1)).norm(), 1e-12);
}

TEST(VertexFrames, MirrorLineSplitsSharedVertices) {
  // A strip of two quads sharing the edge x = 1, whose uvs mirror about it (u = 1 - |x - 1|): the
  // two middle vertices are used by both handednesses and must be split.
  TexturedMesh m;
  m.source = "mirror strip";
  m.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}};
  m.uvs = {{0, 0}, {1, 0}, {0, 0}, {0, 1}, {1, 1}, {0, 1}};
  m.triangles = {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}};
  buildVertexFrames(m);
  EXPECT_EQ(m.positions.size(), 8u);
  for (std::size_t t = 0; t < 4; ++t) {
    const float want = t < 2 ? 1.0f : -1.0f;
    for (std::uint32_t v : m.triangles[t]) EXPECT_EQ(m.handedness[v], want) << "triangle " << t;
  }
}

TEST(VertexFrames, AtlasSeamKeepsSeparateTangents) {
  // The second quad's chart is turned a quarter: its +u runs along +y. The shared edge's vertices
  // are split by their uvs already; their tangents must not be averaged (the texture does not
  // continue there).
  TexturedMesh m;
  m.source = "atlas";
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {4.5, 1}, {4.5, 0}, {5.5, 0}, {5.5, 1}};  // u = 4.5 + y, v = 2 - x
  m.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  buildVertexFrames(m);
  for (std::uint32_t v : m.triangles[0]) EXPECT_LT(angleDeg(m.tangents[v], Eigen::Vector3d::UnitX()), 1e-9);
  for (std::uint32_t v : m.triangles[2]) EXPECT_LT(angleDeg(m.tangents[v], Eigen::Vector3d::UnitY()), 1e-9);
}

TEST(VertexFrames, InterpolatedFrameIsContinuousAcrossEveryEdge) {
  const TexturedMesh m = torus(0.05, 0.015, 24, 12, 0.01).mesh;
  // For each edge shared by two triangles (same positions), the frame at points along it agrees
  // from both sides.
  std::map<std::pair<std::array<double, 3>, std::array<double, 3>>, std::pair<std::uint32_t, std::array<int, 2>>> first;
  auto key = [&](std::uint32_t v) { return std::array<double, 3>{m.positions[v].x(), m.positions[v].y(), m.positions[v].z()}; };
  double worst_n = 0.0, worst_p = 0.0, worst_t = 0.0;
  int edges = 0;
  for (std::uint32_t t = 0; t < m.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = m.triangles[t][std::size_t(k)], b = m.triangles[t][std::size_t((k + 1) % 3)];
      const auto it = first.find({key(b), key(a)});
      if (it == first.end()) {
        first[{key(a), key(b)}] = {t, {k, (k + 1) % 3}};
        continue;
      }
      ++edges;
      const auto [t2, slots] = it->second;
      for (double s : {0.1, 0.5, 0.9}) {
        Eigen::Vector3d b1 = Eigen::Vector3d::Zero(), b2 = Eigen::Vector3d::Zero();
        b1[k] = s;  // from a to b in t ...
        b1[(k + 1) % 3] = 1 - s;
        b2[slots[1]] = s;  // ... and the same point in t2, whose edge runs b -> a
        b2[slots[0]] = 1 - s;
        const SurfaceFrame f1 = frameAt(m, t, b1), f2 = frameAt(m, t2, b2);
        worst_n = std::max(worst_n, angleDeg(f1.normal, f2.normal));
        worst_t = std::max(worst_t, angleDeg(f1.tangent, f2.tangent));
        worst_p = std::max(worst_p, (f1.point - f2.point).norm());
      }
    }
  }
  EXPECT_EQ(edges, int(m.triangles.size()) * 3 / 2);  // closed: every edge found twice
  EXPECT_LT(worst_n, 1e-9);
  EXPECT_LT(worst_t, 1e-9);
  EXPECT_LT(worst_p, 1e-15);
}

TEST(VertexFrames, PhongPointLiesCloserToTheSphere) {
  const double r = 0.05;
  const TexturedMesh m = sphere(r, 24, 12, 0.01).mesh;
  double flat = 0.0, phong = 0.0;
  for (std::uint32_t t = 0; t < m.triangles.size(); ++t) {
    const Eigen::Vector3d b(1.0 / 3, 1.0 / 3, 1.0 / 3);
    flat = std::max(flat, std::fabs(frameAt(m, t, b, FrameMode::Interpolated).point.norm() - r));
    phong = std::max(phong, std::fabs(frameAt(m, t, b, FrameMode::InterpolatedPhong).point.norm() - r));
  }
  EXPECT_GT(flat, 3e-4);       // the centroid's sag at 24 segments: about r (1 - cos(7.5 deg))
  EXPECT_LT(phong, flat / 20);  // measured: 1.0e-5 m against the flat centroids' 5.4e-4 m
}

TEST(VertexFrames, ClosestBarycentricMatchesABruteForceSearch) {
  TexturedMesh m = quad({Eigen::Vector2d(0, 0), {1, 0}, {1, 1}, {0, 1}});
  m.positions[2] = {1.3, 0.7, 0.2};
  const Eigen::Vector3d probes[] = {{0.5, 0.2, 0.3}, {2, 2, -1}, {-1, -1, 0}, {0.9, -0.5, 0.1}, {0.6, 0.5, 5}};
  for (const Eigen::Vector3d& p : probes) {
    const Eigen::Vector3d b = closestBarycentric(m, 0, p);
    const auto& P = m.positions;
    const Eigen::Vector3d q = b.x() * P[0] + b.y() * P[1] + b.z() * P[2];
    double best = 1e9;
    for (int i = 0; i <= 400; ++i) {
      for (int j = 0; i + j <= 400; ++j) {
        const double u = i / 400.0, v = j / 400.0;
        best = std::min(best, ((1 - u - v) * P[0] + u * P[1] + v * P[2] - p).norm());
      }
    }
    EXPECT_LE((q - p).norm(), best + 1e-12);
    EXPECT_GE(b.minCoeff(), 0.0);
    EXPECT_NEAR(b.sum(), 1.0, 1e-12);
  }
}

// A fan of n triangles around the origin, its rim at radius 1 and height rim(k) for rim vertex k.
TexturedMesh fan(int n, double (*rim)(int)) {
  TexturedMesh m;
  m.source = "fan";
  m.positions.push_back(Eigen::Vector3d::Zero());
  m.uvs.push_back(Eigen::Vector2d(0.5, 0.5));
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n;
    m.positions.push_back({std::cos(a), std::sin(a), rim(k)});
    m.uvs.push_back({0.5 + 0.5 * std::cos(a), 0.5 + 0.5 * std::sin(a)});
  }
  for (int k = 0; k < n; ++k) m.triangles.push_back({0, std::uint32_t(1 + k), std::uint32_t(1 + (k + 1) % n)});
  return m;
}

TEST(VertexFrames, AFanOfManyTrianglesAtOneVertexIsLinear) {
  // 50,000 triangles round one smooth vertex: one normal sum for all of them, not a pair of every
  // two (which a file could otherwise use to stall the loader for hours).
  TexturedMesh m = fan(50000, [](int) { return 0.0; });
  buildVertexFrames(m);
  for (const Eigen::Vector3d& n : m.normals) EXPECT_LT((n - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
}

TEST(VertexFrames, RefusesTooManyTrianglesMeetingAcrossCreases) {
  // Rim heights alternating +-1: neighbouring faces differ by about 90 degrees at the centre.
  TexturedMesh m = fan(2 * int(kMaxCreaseValence), [](int k) { return k % 2 ? 1.0 : -1.0; });
  try {
    buildVertexFrames(m);
    FAIL() << "accepted";
  } catch (const thx::Error& e) {
    EXPECT_NE(std::string(e.what()).find("fan: 2048 triangles meet at the vertex at (0.000000, 0.000000, 0.000000) across "
                                         "creases; expected at most 1024"),
              std::string::npos)
        << e.what();
  }
  TexturedMesh small = fan(64, [](int k) { return k % 2 ? 1.0 : -1.0; });
  EXPECT_NO_THROW(buildVertexFrames(small));
}

TEST(VertexFrames, RefusesAZeroAreaTriangleNamingIt) {
  TexturedMesh m = quad({Eigen::Vector2d(0, 0), {1, 0}, {1, 1}, {0, 1}});
  m.positions[2] = {0.5, 0.0, 0.0};  // on the first edge
  try {
    buildVertexFrames(m);
    FAIL() << "accepted";
  } catch (const thx::Error& e) {
    EXPECT_NE(std::string(e.what()).find("quad: triangle 0 has zero area"), std::string::npos) << e.what();
  }
}

}  // namespace test_vertex_frames
