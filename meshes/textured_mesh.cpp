#include "meshes/textured_mesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_map>

#include "base/error.hpp"
#include "meshes/position_key.hpp"

namespace thx::mesh {
namespace {

struct FaceFrame {
  Eigen::Vector3d normal, tangent;
  double area = 0.0;
  double handedness = 1.0;
};

// The unit normal of the triangle p0 p1 p2 (+z for a degenerate one), and its area.
Eigen::Vector3d unitNormal(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                           double& area) {
  const Eigen::Vector3d cross = (p1 - p0).cross(p2 - p0);
  const double len = cross.norm();
  area = 0.5 * len;
  return len > 0.0 ? Eigen::Vector3d(cross / len) : Eigen::Vector3d::UnitZ();
}

// The face normal, area and +u direction from the corner positions and texture coordinates. A
// triangle whose texture coordinates are degenerate (collinear) has no +u direction; it gets its
// first edge, which some tangent is as good as any for a texture that does not vary across it.
FaceFrame faceFrame(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                    const Eigen::Vector2d& t0, const Eigen::Vector2d& t1, const Eigen::Vector2d& t2) {
  FaceFrame f;
  const Eigen::Vector3d e1 = p1 - p0, e2 = p2 - p0;
  f.normal = unitNormal(p0, p1, p2, f.area);
  const Eigen::Vector2d d1 = t1 - t0, d2 = t2 - t0;
  const double r = d1.x() * d2.y() - d2.x() * d1.y();
  const double uv_scale = std::max(d1.squaredNorm(), d2.squaredNorm());
  Eigen::Vector3d t = e1, b = f.normal.cross(e1);
  if (std::fabs(r) > 1e-12 * uv_scale && uv_scale > 0.0) {
    t = (e1 * d2.y() - e2 * d1.y()) / r;
    b = (e2 * d1.x() - e1 * d2.x()) / r;
  }
  t -= f.normal * f.normal.dot(t);
  const double tl = t.norm();
  f.tangent = tl > 0.0 ? Eigen::Vector3d(t / tl) : e1.normalized();
  f.handedness = f.normal.cross(f.tangent).dot(b) < 0.0 ? -1.0 : 1.0;
  return f;
}

double cornerAngle(const Eigen::Vector3d& at, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d u = a - at, v = b - at;
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

// A texture continues between two corners at one position if their coordinates differ by whole
// tiles (a wrapped seam); anything else is a chart boundary of an atlas.
bool sameTexturePoint(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = a - b;
  return std::fabs(d.x() - std::round(d.x())) <= 1e-9 && std::fabs(d.y() - std::round(d.y())) <= 1e-9;
}

Eigen::Vector3d anyPerpendicular(const Eigen::Vector3d& n) {
  const Eigen::Vector3d a = std::fabs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (a - n * n.dot(a)).normalized();
}

}  // namespace

std::size_t TexturedMesh::bytes() const {
  return positions.size() * sizeof(positions[0]) + uvs.size() * sizeof(uvs[0]) +
         triangles.size() * sizeof(triangles[0]) + normals.size() * sizeof(normals[0]) +
         tangents.size() * sizeof(tangents[0]) + handedness.size() * sizeof(handedness[0]);
}

void buildVertexFrames(TexturedMesh& mesh, const FrameOptions& options) {
  const std::size_t nt = mesh.triangles.size(), nv = mesh.positions.size();
  if (nt == 0) throw Error(Error::Kind::Config, "mesh " + mesh.source + ": no triangles");
  if (mesh.uvs.size() != nv) {
    throw Error(Error::Kind::Config, "mesh " + mesh.source + ": " + std::to_string(mesh.uvs.size()) +
                                         " texture coordinates for " + std::to_string(nv) + " vertices");
  }
  std::vector<FaceFrame> faces(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const Triangle& tri = mesh.triangles[t];
    for (std::uint32_t v : tri) {
      if (v >= nv) {
        throw Error(Error::Kind::Config, "mesh " + mesh.source + ": triangle " + std::to_string(t) +
                                             " uses vertex " + std::to_string(v) + " of " + std::to_string(nv));
      }
    }
    faces[t] = faceFrame(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]], mesh.uvs[tri[0]],
                         mesh.uvs[tri[1]], mesh.uvs[tri[2]]);
    if (!(faces[t].area > 0.0)) {
      throw Error(Error::Kind::Config,
                  "mesh " + mesh.source + ": triangle " + std::to_string(t) + " has zero area; expected none");
    }
  }

  // Corners (triangle * 3 + slot) grouped by the position of their vertex, in a flat table.
  std::unordered_map<PositionBits, std::uint32_t, PositionHash> group_of_position;
  group_of_position.reserve(nv);
  std::vector<std::uint32_t> group_of_vertex(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    group_of_vertex[v] = group_of_position.try_emplace(bitsOf(mesh.positions[v]), std::uint32_t(group_of_position.size()))
                             .first->second;
  }
  const std::size_t ng = group_of_position.size();
  std::vector<std::uint32_t> group_start(ng + 1, 0), corners(3 * nt);
  for (const Triangle& tri : mesh.triangles) {
    for (std::uint32_t v : tri) ++group_start[group_of_vertex[v] + 1];
  }
  for (std::size_t g = 0; g < ng; ++g) group_start[g + 1] += group_start[g];
  {
    std::vector<std::uint32_t> fill(group_start.begin(), group_start.end() - 1);
    for (std::size_t c = 0; c < 3 * nt; ++c) corners[fill[group_of_vertex[mesh.triangles[c / 3][c % 3]]]++] = std::uint32_t(c);
  }
  auto angleAt = [&](std::uint32_t c) {
    const Triangle& tri = mesh.triangles[c / 3];
    const std::size_t k = c % 3;
    return cornerAngle(mesh.positions[tri[k]], mesh.positions[tri[(k + 1) % 3]], mesh.positions[tri[(k + 2) % 3]]);
  };

  const double cos_crease = std::cos(options.crease_angle_deg * M_PI / 180.0);
  struct Frame {
    Eigen::Vector3d n, t;
    float h;
    std::uint32_t index;
  };
  std::vector<std::vector<Frame>> frames_of_vertex(nv);  // distinct frames each vertex needs
  std::vector<Eigen::Vector3d> out_positions, out_normals, out_tangents;
  std::vector<Eigen::Vector2d> out_uvs;
  std::vector<float> out_handedness;
  out_positions.reserve(nv);
  std::vector<Triangle> out_triangles(nt);

  // The sums of each corner's normal and tangent over the corners at its position (the header's
  // rules). Where every face at a position lies within half the crease angle of their mean normal
  // (a smooth vertex, however many faces meet there: a sphere's pole), every pair of them is
  // within the crease angle, so one normal sum serves all its corners and the tangents are summed
  // per class of handedness and texture point (a sort): linear in the faces. Elsewhere (a crease)
  // each corner compares with every other, bounded by kMaxCreaseValence so a file cannot make
  // the work quadratic in its size.
  std::vector<Eigen::Vector3d> corner_n(3 * nt), corner_t(3 * nt);
  const double cos_half_crease = std::cos(options.crease_angle_deg * M_PI / 360.0);
  struct Keyed {
    std::array<long long, 3> key;
    std::uint32_t corner;
  };
  std::vector<Keyed> scratch;
  auto textureClass = [&](std::uint32_t corner) {
    const Eigen::Vector2d& uv = mesh.uvs[mesh.triangles[corner / 3][corner % 3]];
    auto frac = [](double x) { return (std::llround((x - std::floor(x)) * 1e9)) % 1000000000ll; };
    return std::array<long long, 3>{faces[corner / 3].handedness > 0 ? 1 : -1, frac(uv.x()), frac(uv.y())};
  };
  for (std::size_t g = 0; g < ng; ++g) {
    const std::uint32_t* first = corners.data() + group_start[g];
    const std::uint32_t* last = corners.data() + group_start[g + 1];
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const std::uint32_t* c = first; c != last; ++c) mean += faces[*c / 3].normal;
    bool smooth = mean.norm() > 0.0;
    if (smooth) mean.normalize();
    for (const std::uint32_t* c = first; c != last && smooth; ++c) smooth = faces[*c / 3].normal.dot(mean) >= cos_half_crease;
    if (smooth) {
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      for (const std::uint32_t* c = first; c != last; ++c) n += angleAt(*c) * faces[*c / 3].normal;
      scratch.clear();
      for (const std::uint32_t* c = first; c != last; ++c) scratch.push_back({textureClass(*c), *c});
      std::sort(scratch.begin(), scratch.end(), [](const Keyed& a, const Keyed& b) {
        return a.key != b.key ? a.key < b.key : a.corner < b.corner;
      });
      for (std::size_t a = 0; a < scratch.size();) {
        std::size_t b = a;
        Eigen::Vector3d tan = Eigen::Vector3d::Zero();
        for (; b < scratch.size() && scratch[b].key == scratch[a].key; ++b) {
          const FaceFrame& f = faces[scratch[b].corner / 3];
          tan += f.area * f.tangent;
        }
        for (std::size_t k = a; k < b; ++k) {
          corner_n[scratch[k].corner] = n;
          corner_t[scratch[k].corner] = tan;
        }
        a = b;
      }
      continue;
    }
    if (last - first > kMaxCreaseValence) {
      const Eigen::Vector3d& p = mesh.positions[mesh.triangles[*first / 3][*first % 3]];
      throw Error(Error::Kind::Config, "mesh " + mesh.source + ": " + std::to_string(last - first) +
                                           " triangles meet at the vertex at (" + std::to_string(p.x()) + ", " +
                                           std::to_string(p.y()) + ", " + std::to_string(p.z()) +
                                           ") across creases; expected at most " + std::to_string(kMaxCreaseValence));
    }
    for (const std::uint32_t* c = first; c != last; ++c) {
      const FaceFrame& own = faces[*c / 3];
      const std::uint32_t v = mesh.triangles[*c / 3][*c % 3];
      Eigen::Vector3d n = Eigen::Vector3d::Zero(), tan = Eigen::Vector3d::Zero();
      for (const std::uint32_t* o = first; o != last; ++o) {
        const FaceFrame& f = faces[*o / 3];
        if (f.normal.dot(own.normal) < cos_crease) continue;
        n += angleAt(*o) * f.normal;
        const std::uint32_t ov = mesh.triangles[*o / 3][*o % 3];
        if (f.handedness == own.handedness && sameTexturePoint(mesh.uvs[ov], mesh.uvs[v])) tan += f.area * f.tangent;
      }
      corner_n[*c] = n;
      corner_t[*c] = tan;
    }
  }

  for (std::size_t c = 0; c < 3 * nt; ++c) {
    const std::size_t t = c / 3;
    const std::uint32_t v = mesh.triangles[t][c % 3];
    const FaceFrame& own = faces[t];
    Eigen::Vector3d n = corner_n[c], tan = corner_t[c];
    const double nl = n.norm();
    n = nl > 0.0 ? Eigen::Vector3d(n / nl) : own.normal;
    tan -= n * n.dot(tan);
    if (tan.norm() <= 1e-12 * own.area) tan = own.tangent - n * n.dot(own.tangent);
    const double tl = tan.norm();
    tan = tl > 1e-12 ? Eigen::Vector3d(tan / tl) : anyPerpendicular(n);
    const float h = float(own.handedness);

    std::uint32_t index = 0;
    bool found = false;
    for (const Frame& fr : frames_of_vertex[v]) {
      if (fr.n == n && fr.t == tan && fr.h == h) {
        index = fr.index;
        found = true;
        break;
      }
    }
    if (!found) {
      index = std::uint32_t(out_positions.size());
      frames_of_vertex[v].push_back({n, tan, h, index});
      out_positions.push_back(mesh.positions[v]);
      out_uvs.push_back(mesh.uvs[v]);
      out_normals.push_back(n);
      out_tangents.push_back(tan);
      out_handedness.push_back(h);
    }
    out_triangles[t][c % 3] = index;
  }
  mesh.positions = std::move(out_positions);
  mesh.uvs = std::move(out_uvs);
  mesh.triangles = std::move(out_triangles);
  mesh.normals = std::move(out_normals);
  mesh.tangents = std::move(out_tangents);
  mesh.handedness = std::move(out_handedness);
}

std::vector<Triangle> triangleNeighbours(const TexturedMesh& mesh) {
  // Sorted, not hashed: a hash table of 3 million directed edges (a 1,000,000-triangle sphere)
  // took 2.5 s, a cache miss per lookup; sorting the same edges as integer pairs takes a tenth.
  // Each distinct position (by its bits, position_key.hpp) gets an index, so a seam's split
  // vertices are one point.
  const std::size_t nv = mesh.positions.size();
  std::vector<PositionBits> bits(nv);
  std::vector<std::uint32_t> order(nv), point(nv);
  for (std::size_t v = 0; v < nv; ++v) bits[v] = bitsOf(mesh.positions[v]), order[v] = std::uint32_t(v);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return bits[a] < bits[b]; });
  std::uint32_t points = 0;
  for (std::size_t r = 0; r < nv; ++r) {
    if (r > 0 && bits[order[r]] != bits[order[r - 1]]) ++points;
    point[order[r]] = points;
  }
  // Every edge as (its ends' points, lower first; the corner opposite it; whether it runs from
  // the lower point), sorted so that the edges between two points are adjacent.
  struct Edge {
    std::uint64_t ends;
    std::uint32_t corner;  // 3 t + k
    bool upward;           // from its lower point to its higher
  };
  std::vector<Edge> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t from = point[mesh.triangles[t][(k + 1) % 3]], to = point[mesh.triangles[t][(k + 2) % 3]];
      const std::uint32_t lo = std::min(from, to), hi = std::max(from, to);
      edges.push_back({(std::uint64_t(lo) << 32) | hi, std::uint32_t(3 * t + k), from < to});
    }
  std::sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) { return a.ends < b.ends; });
  // Two triangles are neighbours across an edge that exactly one runs each way; an edge run twice
  // the same way, or by more than two triangles, joins none. (A zero-length edge, both ends one
  // point, runs "both ways" at once: its triangle is its own neighbour there if no other edge
  // has those ends.)
  std::vector<Triangle> out(mesh.triangles.size(), Triangle{kNoNeighbour, kNoNeighbour, kNoNeighbour});
  for (std::size_t a = 0; a < edges.size();) {
    std::size_t b = a + 1;
    while (b < edges.size() && edges[b].ends == edges[a].ends) ++b;
    const bool point_edge = (edges[a].ends >> 32) == (edges[a].ends & 0xffffffffu);
    if (point_edge && b - a == 1) {
      out[edges[a].corner / 3][edges[a].corner % 3] = edges[a].corner / 3;
    } else if (!point_edge && b - a == 2 && edges[a].upward != edges[a + 1].upward) {
      out[edges[a].corner / 3][edges[a].corner % 3] = edges[a + 1].corner / 3;
      out[edges[a + 1].corner / 3][edges[a + 1].corner % 3] = edges[a].corner / 3;
    }
    a = b;
  }
  return out;
}

void triangleFrame(const TexturedMesh& mesh, std::uint32_t triangle, Eigen::Vector3d& normal, Eigen::Vector3d& tangent,
                   double& handedness) {
  const Triangle& t = mesh.triangles[triangle];
  const FaceFrame f = faceFrame(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], mesh.uvs[t[0]],
                                mesh.uvs[t[1]], mesh.uvs[t[2]]);
  normal = f.normal;
  tangent = f.tangent;
  handedness = f.handedness;
}

Eigen::Vector3d faceNormal(const TexturedMesh& mesh, std::uint32_t triangle) {
  const Triangle& t = mesh.triangles[triangle];
  double area = 0.0;
  return unitNormal(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], area);
}

Eigen::Vector2d metresPerUv(const TexturedMesh& mesh, std::uint32_t triangle, const SurfaceFrame& frame) {
  const Triangle& t = mesh.triangles[triangle];
  const Eigen::Vector3d e1 = mesh.positions[t[1]] - mesh.positions[t[0]];
  const Eigen::Vector3d e2 = mesh.positions[t[2]] - mesh.positions[t[0]];
  const Eigen::Vector2d d1 = mesh.uvs[t[1]] - mesh.uvs[t[0]], d2 = mesh.uvs[t[2]] - mesh.uvs[t[0]];
  const double r = d1.x() * d2.y() - d2.x() * d1.y();
  double sx = 1.0, sy = 1.0;
  if (std::fabs(r) > 0.0) {
    sx = ((e1 * d2.y() - e2 * d1.y()) / r).dot(frame.tangent);
    sy = ((e2 * d1.x() - e1 * d2.x()) / r).dot(frame.bitangent);
  }
  if (!(sx > 0.0) || !std::isfinite(sx)) sx = 1.0;
  if (!(sy > 0.0) || !std::isfinite(sy)) sy = 1.0;
  return {sx, sy};
}

SurfaceFrame frameAt(const TexturedMesh& mesh, std::uint32_t triangle, const Eigen::Vector3d& b, FrameMode mode) {
  const Triangle& t = mesh.triangles[triangle];
  SurfaceFrame f;
  const Eigen::Vector3d& p0 = mesh.positions[t[0]];
  const Eigen::Vector3d& p1 = mesh.positions[t[1]];
  const Eigen::Vector3d& p2 = mesh.positions[t[2]];
  f.point = b.x() * p0 + b.y() * p1 + b.z() * p2;
  f.uv = b.x() * mesh.uvs[t[0]] + b.y() * mesh.uvs[t[1]] + b.z() * mesh.uvs[t[2]];
  if (mode == FrameMode::PerTriangle) {
    double h = 1.0;
    triangleFrame(mesh, triangle, f.normal, f.tangent, h);
    f.bitangent = h * f.normal.cross(f.tangent);
    return f;
  }
  const Eigen::Vector3d& n0 = mesh.normals[t[0]];
  const Eigen::Vector3d& n1 = mesh.normals[t[1]];
  const Eigen::Vector3d& n2 = mesh.normals[t[2]];
  Eigen::Vector3d n = b.x() * n0 + b.y() * n1 + b.z() * n2;
  const double nl = n.norm();
  // Interpolated unit normals shorten between diverging corners but cannot cancel within a crease
  // angle below 180 degrees; the guard only keeps a NaN out of a corrupted mesh.
  n = nl > 1e-12 ? Eigen::Vector3d(n / nl) : n0;
  Eigen::Vector3d tan = b.x() * mesh.tangents[t[0]] + b.y() * mesh.tangents[t[1]] + b.z() * mesh.tangents[t[2]];
  tan -= n * n.dot(tan);
  const double tl = tan.norm();
  tan = tl > 1e-12 ? Eigen::Vector3d(tan / tl) : anyPerpendicular(n);
  f.normal = n;
  f.tangent = tan;
  f.bitangent = double(mesh.handedness[t[0]]) * n.cross(tan);
  if (mode == FrameMode::InterpolatedPhong) {
    // Phong tessellation's shape factor 1/2: on a circle it puts an edge's midpoint on the arc to
    // second order (1 overshoots by the flat chord's sag; Boubekeur and Alexa's 3/4 is for looks).
    const Eigen::Vector3d p = f.point;
    f.point = p - 0.5 * (b.x() * n0 * (p - p0).dot(n0) + b.y() * n1 * (p - p1).dot(n1) + b.z() * n2 * (p - p2).dot(n2));
  }
  return f;
}

Eigen::Vector3d closestBarycentric(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                   const Eigen::Vector3d& p) {
  // Ericson, Real-Time Collision Detection, 5.1.5: the Voronoi regions of vertices, edges, face.
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {1.0, 0.0, 0.0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {0.0, 1.0, 0.0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double w = d1 / (d1 - d3);
    return {1.0 - w, w, 0.0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {0.0, 0.0, 1.0};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return {1.0 - w, 0.0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0.0, 1.0 - w, w};
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1.0 - v - w, v, w};
}

std::uint32_t nearestTriangle(const TexturedMesh& mesh, const Eigen::Vector3d& p) {
  std::uint32_t best = 0;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const double d2 = (pointAt(mesh, t, closestBarycentric(mesh, t, p)) - p).squaredNorm();
    if (d2 < best_d2) best_d2 = d2, best = t;
  }
  return best;
}

}  // namespace thx::mesh
