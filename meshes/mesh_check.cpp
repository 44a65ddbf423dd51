#include "meshes/mesh_check.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include "base/error.hpp"
#include "base/number_text.hpp"
#include "meshes/position_key.hpp"

// Helpers in a namespace of this file's own: the target's sources are compiled in unity batches,
// which would join their anonymous namespaces (docs/build.md).
namespace thx::mesh::mesh_check {
namespace {

[[noreturn]] void refuse(const TexturedMesh& mesh, const std::string& what) {
  throw Error(Error::Kind::Config, "mesh " + mesh.source + ": " + what);
}

std::string n(std::size_t k) { return std::to_string(k); }

std::string triangleText(std::size_t t, const Triangle& tri) {
  return "triangle " + n(t) + " (" + n(tri[0]) + ", " + n(tri[1]) + ", " + n(tri[2]) + ")";
}

void checkCounts(const TexturedMesh& mesh, const MeshLimits& limits) {
  if (mesh.triangles.empty()) refuse(mesh, "no triangles; expected at least one");
  if (mesh.triangles.size() > limits.max_triangles) {
    refuse(mesh, n(mesh.triangles.size()) + " triangles, more than the limit of " + n(limits.max_triangles) +
                     " (MeshLimits::max_triangles)");
  }
  // Corners (3 per triangle) and vertices are numbered in 32 bits, as the triangles' indices are.
  constexpr std::size_t kMax32 = std::numeric_limits<std::uint32_t>::max();
  if (mesh.triangles.size() > kMax32 / 3 || mesh.positions.size() > kMax32) {
    refuse(mesh, n(mesh.triangles.size()) + " triangles and " + n(mesh.positions.size()) + " vertices; expected at most " +
                     n(kMax32 / 3) + " and " + n(kMax32));
  }
  if (mesh.uvs.size() != mesh.positions.size()) {
    refuse(mesh, n(mesh.uvs.size()) + " texture coordinates for " + n(mesh.positions.size()) +
                     " vertices; expected one per vertex (a mesh without texture coordinates needs a projection)");
  }
}

void checkFinite(const TexturedMesh& mesh) {
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const Eigen::Vector3d& p = mesh.positions[v];
    if (!p.allFinite()) {
      refuse(mesh, "vertex " + n(v) + " has a non-finite position (" + numberText(p.x()) + ", " + numberText(p.y()) +
                       ", " + numberText(p.z()) + "); expected finite coordinates");
    }
    const Eigen::Vector2d& t = mesh.uvs[v];
    if (!t.allFinite()) {
      refuse(mesh, "vertex " + n(v) + " has a non-finite texture coordinate (" + numberText(t.x()) + ", " +
                       numberText(t.y()) + "); expected finite coordinates");
    }
  }
}

void checkTriangles(const TexturedMesh& mesh) {
  const std::size_t nv = mesh.positions.size();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    for (std::uint32_t v : tri) {
      if (v >= nv) {
        refuse(mesh, triangleText(t, tri) + " uses vertex " + n(v) + ", but the mesh has " + n(nv) +
                         " vertices; expected indices below " + n(nv));
      }
    }
    for (int k = 0; k < 3; ++k) {
      if (tri[std::size_t(k)] == tri[std::size_t((k + 1) % 3)]) {
        refuse(mesh, triangleText(t, tri) + " repeats vertex " + n(tri[std::size_t(k)]) +
                         "; expected three different vertices");
      }
    }
  }
}

// Zero area relative to the mesh's size: a sliver of 1e-12 of the bounding box's diagonal squared
// carries no direction a frame could be built from (buildVertexFrames divides by it).
void checkAreas(const TexturedMesh& mesh) {
  Eigen::Vector3d lo = mesh.positions[0], hi = mesh.positions[0];
  for (const Eigen::Vector3d& p : mesh.positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double min_area = 1e-12 * (hi - lo).squaredNorm();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    const Eigen::Vector3d& a = mesh.positions[tri[0]];
    const double area = 0.5 * (mesh.positions[tri[1]] - a).cross(mesh.positions[tri[2]] - a).norm();
    if (!(area > min_area)) {
      refuse(mesh, triangleText(t, tri) + " has area " + numberText(area) +
                       " m^2; expected more than 1e-12 x the bounding-box diagonal squared (" + numberText(min_area) +
                       " m^2)");
    }
  }
}

// Edges between positions, found without a hash table of edges: each triangle edge is filed
// under the lower of its two position ids (a counting sort, O(n)), each position's few edges
// sorted by the other end, so one edge's triangles lie together in triangle order. A fan of a
// million triangles around one position costs a sort of a million, not a million squared.
void checkEdges(const TexturedMesh& mesh, const MeshLimits& limits) {
  const std::size_t nt = mesh.triangles.size();
  std::vector<std::uint32_t> position_id(mesh.positions.size());
  std::size_t np = 0;
  {
    std::unordered_map<PositionBits, std::uint32_t, PositionHash> id_of_position;
    id_of_position.reserve(mesh.positions.size());
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      position_id[v] =
          id_of_position.try_emplace(bitsOf(mesh.positions[v]), std::uint32_t(id_of_position.size())).first->second;
    }
    np = id_of_position.size();
  }
  // Corner c = 3 t + k starts edge k of triangle t, which runs from corner k to corner k + 1. The
  // corners of a triangle of positive area are three different positions (checkAreas).
  const auto from = [&](std::uint32_t c) { return mesh.triangles[c / 3][c % 3]; };
  const auto to = [&](std::uint32_t c) { return mesh.triangles[c / 3][(c % 3 + 1) % 3]; };
  const auto upward = [&](std::uint32_t c) { return position_id[from(c)] < position_id[to(c)]; };
  const auto lower = [&](std::uint32_t c) { return std::min(position_id[from(c)], position_id[to(c)]); };
  const auto upper = [&](std::uint32_t c) { return std::max(position_id[from(c)], position_id[to(c)]); };

  const auto nc = std::uint32_t(3 * nt);
  std::vector<std::uint32_t> first(np + 1, 0);
  for (std::uint32_t c = 0; c < nc; ++c) ++first[lower(c) + 1];
  for (std::size_t p = 0; p < np; ++p) first[p + 1] += first[p];
  std::vector<std::uint64_t> filed(nc);  // upper position id << 32 | corner, by lower position id
  {
    std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
    for (std::uint32_t c = 0; c < nc; ++c) filed[next[lower(c)]++] = std::uint64_t(upper(c)) << 32 | c;
  }

  // The problem reported is the one a walk through the triangles in order meets first: the
  // smallest first corner of a bad edge.
  enum class Problem { None, Winding, Hole, NonManifold } problem = Problem::None;
  std::uint32_t at = nc;
  std::size_t run_start = 0, run_count = 0;
  for (std::size_t p = 0; p < np; ++p) {
    std::sort(filed.begin() + first[p], filed.begin() + first[p + 1]);
    for (std::size_t i = first[p]; i < first[p + 1];) {
      std::size_t e = i + 1;
      while (e < first[p + 1] && filed[e] >> 32 == filed[i] >> 32) ++e;
      const auto c0 = std::uint32_t(filed[i]);
      Problem found = Problem::None;
      if (e - i == 2 && upward(c0) == upward(std::uint32_t(filed[i + 1]))) found = Problem::Winding;
      else if (limits.require_closed && e - i == 1) found = Problem::Hole;
      else if (limits.require_closed && e - i > 2) found = Problem::NonManifold;
      if (found != Problem::None && c0 < at) problem = found, at = c0, run_start = i, run_count = e - i;
      i = e;
    }
  }
  if (problem == Problem::None) return;

  const std::size_t t = at / 3;
  const std::string run = n(from(at)) + "->" + n(to(at));
  const auto triangleOf = [&](std::size_t k) { return n(std::uint32_t(filed[run_start + k]) / 3); };
  if (problem == Problem::Winding) {
    refuse(mesh, "triangles " + n(t) + " and " + triangleOf(1) + " both run edge " + run +
                     ": inconsistent winding; expected neighbouring triangles to run a shared edge in opposite "
                     "directions (counter-clockwise seen from outside)");
  }
  if (problem == Problem::Hole) {
    refuse(mesh, "edge " + run + " of " + triangleText(t, mesh.triangles[t]) +
                     " belongs to no other triangle (a hole); expected every edge shared by exactly two triangles (a "
                     "closed surface)");
  }
  const std::string more = run_count > 3 ? " and " + n(run_count - 3) + " more" : "";
  refuse(mesh, "edge " + run + " of triangle " + n(t) + " is shared by " + n(run_count) + " triangles (" + n(t) + ", " +
                   triangleOf(1) + ", " + triangleOf(2) + more +
                   "); expected every edge shared by exactly two triangles (a closed surface)");
}

void checkAll(const TexturedMesh& mesh, const MeshLimits& limits) {
  checkCounts(mesh, limits);
  checkFinite(mesh);
  checkTriangles(mesh);
  checkAreas(mesh);
  checkEdges(mesh, limits);
}

}  // namespace
}  // namespace thx::mesh::mesh_check

namespace thx::mesh {

void checkMesh(const TexturedMesh& mesh, const MeshLimits& limits) { mesh_check::checkAll(mesh, limits); }

}  // namespace thx::mesh
