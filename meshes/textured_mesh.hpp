#pragma once
// A triangle mesh that carries a texture: positions, texture coordinates and one tangent frame per
// vertex (normal, tangent along +u, handedness), the frames every sense interpolates at a contact
// (docs/design.md §7: the frames that shade a pixel are the frames that turn a texel into a force).
//
// Conventions (docs/meshes.md):
//  - positions in metres in the mesh's own frame; triangles counter-clockwise seen from outside.
//  - uv: texture coordinates, 1 = one texture tile; the texture's tangent frame (textures/
//    texture_map.hpp: +x = +u, +y = +v, +z = out) maps to (tangent, bitangent, normal) with
//    bitangent = handedness * normal x tangent. Handedness -1 is a mirrored chart.
//  - frames (buildVertexFrames): a vertex's normal is the angle-weighted mean of the face normals
//    around its position that lie within the crease angle of the face it is used by (a box keeps
//    its edges; a sphere is smooth across every edge and across its texture seam); its tangent the
//    area-weighted mean of those faces' +u directions with the same handedness and a texture that
//    continues (texture coordinates equal up to whole tiles: a wrapped seam is smooth, an atlas
//    seam is not), made orthogonal to the normal (Gram-Schmidt). A vertex whose corners get
//    different frames is split, so every triangle reads its three corners' frames by index.
//
// Built once, before any real-time use (allocates). frameAt() is real-time safe.
#include <Eigen/Core>
#include <Eigen/Geometry>  // cross(): every user of a frame needs it
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace thx::mesh {

using Triangle = std::array<std::uint32_t, 3>;

struct TexturedMesh {
  std::string source;  // the file or generator it came from, for error messages
  std::vector<Eigen::Vector3d> positions;
  std::vector<Eigen::Vector2d> uvs;  // one per position
  std::vector<Triangle> triangles;
  // Filled by buildVertexFrames (empty before): unit normal, unit tangent orthogonal to it, +-1.
  std::vector<Eigen::Vector3d> normals;
  std::vector<Eigen::Vector3d> tangents;
  std::vector<float> handedness;

  bool hasFrames() const { return !normals.empty() && normals.size() == positions.size(); }
  std::size_t bytes() const;
};

// At most this many triangles may meet at one position across creases (a position where faces
// differ by more than half the crease angle compares every pair of them); a smooth vertex has no
// bound.
inline constexpr long kMaxCreaseValence = 1024;

struct FrameOptions {
  // Faces meeting at a sharper angle keep separate normals (a hard edge). 60 degrees keeps a box's
  // 90-degree edges hard and smooths any tessellation of a curved surface coarser than 6 faces
  // per circle.
  double crease_angle_deg = 60.0;
};

// Computes normals, tangents and handedness, splitting vertices where the frames differ; time
// linear in the triangles. Throws thx::Error (Config) naming mesh.source if the mesh has no
// triangles, a triangle has zero area (mesh_check.hpp catches those with a better message
// first) or more than kMaxCreaseValence triangles meet at a crease vertex.
void buildVertexFrames(TexturedMesh& mesh, const FrameOptions& options = {});

// The frame at a point of one triangle, from barycentric coordinates b (b >= 0, sum 1).
struct SurfaceFrame {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // on the flat triangle, or Phong's (below)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d tangent = Eigen::Vector3d::UnitX();
  Eigen::Vector3d bitangent = Eigen::Vector3d::UnitY();
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
};

enum class FrameMode {
  PerTriangle,      // the triangle's own normal and +u direction, flat point (CHAI3D 3.3's frame)
  Interpolated,     // vertex frames interpolated barycentrically, flat point (force shading)
  InterpolatedPhong,  // the same, the point moved onto Phong's curved triangle (Boubekeur and
                      // Alexa 2008, shape factor 1/2): the smooth surface the vertex normals describe
};

// Requires hasFrames(). Real-time safe.
SurfaceFrame frameAt(const TexturedMesh& mesh, std::uint32_t triangle, const Eigen::Vector3d& b,
                     FrameMode mode = FrameMode::InterpolatedPhong);

// A texture's tangent-space direction n (textures/texture_map.hpp: +x = +u, +y = +v, +z out) in
// the frame's axes, unit: how the haptic chart, the physics contacts and the shaders read a
// texel's normal on a mesh. Real-time safe.
inline Eigen::Vector3d fromTangentSpace(const SurfaceFrame& frame, const Eigen::Vector3d& n) {
  return (n.x() * frame.tangent + n.y() * frame.bitangent + n.z() * frame.normal).normalized();
}

// Metres per uv unit along the frame's tangent and bitangent on this triangle (its texture
// mapping: d position / d uv, projected on the frame's axes): the scale the texture is laid at
// there. A triangle whose mapping folds against the frame, or is degenerate, has no meaningful
// scale: 1 m per uv unit on that axis. The haptic chart (server/textured_mesh_renderer.hpp) and
// the visual client's shaders and CPU reference read the texture at this scale, so what is felt
// and what is seen agree. Real-time safe.
Eigen::Vector2d metresPerUv(const TexturedMesh& mesh, std::uint32_t triangle, const SurfaceFrame& frame);

// The triangle's own frame (FrameMode::PerTriangle): unit normal, unit +u direction in its plane.
void triangleFrame(const TexturedMesh& mesh, std::uint32_t triangle, Eigen::Vector3d& normal,
                   Eigen::Vector3d& tangent, double& handedness);
// The triangle's own unit normal (triangleFrame's, to the bit), as every sense reads a flat face.
// Without the tangent: the physics asks it of every triangle within an object's reach each step
// (chart_boundary.cpp), where the whole frame took a tenth of a bump-mapped marble's step.
Eigen::Vector3d faceNormal(const TexturedMesh& mesh, std::uint32_t triangle);

// For each triangle, the triangle across each of its edges: [k] shares the edge opposite corner k
// (corners k+1, k+2), matched by the positions of its ends (a seam's split vertices still join);
// kNoNeighbour on a border or an edge of more than two triangles. Built once (allocates).
inline constexpr std::uint32_t kNoNeighbour = 0xffffffffu;
std::vector<Triangle> triangleNeighbours(const TexturedMesh& mesh);

// Barycentric coordinates of the point of triangle (a, b, c) closest to p (each >= 0, summing
// to 1). Real-time safe.
Eigen::Vector3d closestBarycentric(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                   const Eigen::Vector3d& p);
inline Eigen::Vector3d closestBarycentric(const TexturedMesh& mesh, std::uint32_t triangle, const Eigen::Vector3d& p) {
  const Triangle& t = mesh.triangles[triangle];
  return closestBarycentric(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], p);
}
// The point at barycentric b of `triangle` (flat). Real-time safe.
inline Eigen::Vector3d pointAt(const TexturedMesh& mesh, std::uint32_t triangle, const Eigen::Vector3d& b) {
  const Triangle& t = mesh.triangles[triangle];
  return b.x() * mesh.positions[t[0]] + b.y() * mesh.positions[t[1]] + b.z() * mesh.positions[t[2]];
}
// The triangle whose closest point is nearest p, by looking at every one (O(triangles): where a
// walk over the mesh has no triangle to start from; not for the servo tick).
std::uint32_t nearestTriangle(const TexturedMesh& mesh, const Eigen::Vector3d& p);

}  // namespace thx::mesh
