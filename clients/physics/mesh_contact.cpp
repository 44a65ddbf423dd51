#include "clients/physics/mesh_contact.hpp"

#include <BulletCollision/BroadphaseCollision/btBroadphaseProxy.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <unordered_map>

#include "clients/physics/bullet_convert.hpp"
#include "clients/physics/crease_contact.hpp"
#include "meshes/position_key.hpp"
#include "textures/textured_surface.hpp"

namespace thx::phys {


Eigen::Vector3d meshTextureNormal(const mesh::TexturedMesh& mesh, std::uint32_t triangle, const mesh::SurfaceFrame& f,
                                  Eigen::Vector3d n_tangent, const MeshContactOptions& options) {
  if (options.normals_made_for_m.minCoeff() > 0.0)
    n_tangent = tex::scaleSlopes(n_tangent, options.normals_made_for_m.cwiseQuotient(mesh::metresPerUv(mesh, triangle, f)));
  return clampTilt(mesh::fromTangentSpace(f, n_tangent), f.normal, options.max_tilt_deg);
}

Eigen::Vector3d meshContactNormal(const mesh::TexturedMesh& mesh, std::uint32_t triangle, const Eigen::Vector3d& b,
                                  const MeshContactOptions& options) {
  const mesh::SurfaceFrame f = mesh::frameAt(mesh, triangle, b, mesh::FrameMode::Interpolated);
  if (!options.texture) return f.normal;
  const tex::TexCoord uv{f.uv.x(), f.uv.y()};
  const tex::Sample s = tex::sample(*options.texture, uv, options.sampling);
  return meshTextureNormal(mesh, triangle, f, s.normal.cast<double>(), options);
}

Eigen::Vector2d metresPerUvAt(const ContactMesh& contact_mesh, std::uint32_t triangle, const Eigen::Vector3d& b) {
  const mesh::Triangle& t = contact_mesh.mesh->triangles[triangle];
  return b.x() * contact_mesh.metres_per_uv[t[0]] + b.y() * contact_mesh.metres_per_uv[t[1]] + b.z() * contact_mesh.metres_per_uv[t[2]];
}

namespace {

// The lift of a ball of radius r on the relief of `triangle` at barycentric b, met from the front
// (front: the side its winding faces) or from behind; in metres where the texture is laid (no
// rescaling to the tile it was made for).
// `near`: a texel touched nearby, to start the search from (BallOnRelief::touch), updated to this
// search's.
double liftOnFace(const ContactMesh& contact_mesh, std::uint32_t triangle, const Eigen::Vector3d& b, bool front,
                  double r, const MeshContactOptions& options, std::optional<tex::BallOnRelief::Texel>* near = nullptr) {
  const auto touched = [&](const tex::BallOnRelief::Touch& t) {
    if (near) *near = t.texel;
    return t;
  };
  const mesh::SurfaceFrame f = mesh::frameAt(*contact_mesh.mesh, triangle, b, mesh::FrameMode::Interpolated);
  const Eigen::Vector2d metres_per_uv = metresPerUvAt(contact_mesh, triangle, b);
  const double big_r = options.sphere_radius_m;
  const std::optional<tex::BallOnRelief::Texel> start = near ? *near : std::nullopt;
  if (!(big_r > 0.0)) return touched(options.ball_relief->touch({f.uv.x(), f.uv.y()}, metres_per_uv, r, !front, start)).lift_m;
  // On a sphere (MeshContactOptions::sphere_radius_m): the touch searched with the distances
  // stretched for the sphere's sag, then the centre's distance for the point it found taken
  // exactly: that point at height h over the smooth sphere and an arc rho from the foot lies on the
  // sphere of radius s = R + h, an angle rho / R off the centre's line, so the ball's centre stands
  // s cos(phi) + sqrt(r^2 - s^2 sin^2(phi)) from the sphere's centre. (The stretch alone is exact
  // at h = 0 only; on the dimpled ball's floors, 0.25 mm down, it read the marble's swing 3 % slow.)
  const double stretch = std::sqrt(std::max(1e-3, 1.0 + (front ? r : -r) / big_r));
  const tex::BallOnRelief::Touch touch =
      touched(options.ball_relief->touch({f.uv.x(), f.uv.y()}, stretch * metres_per_uv, r, !front, start));
  if (!front) return touch.lift_m;  // a ball inside a textured ball: the stretch alone
  const double h = touch.lift_m + r - r * touch.normal.z();
  const double phi = r * touch.normal.head<2>().norm() / stretch / big_r;
  const double s = big_r + h;
  return s * std::cos(phi) + std::sqrt(std::max(0.0, r * r - s * s * std::sin(phi) * std::sin(phi))) - big_r - r;
}

// With `half` (BallOnRelief::touchOnHalf; flat faces only), that side's relief alone: nullopt where
// it holds no texel.
std::optional<double> liftOnFaceHalf(const ContactMesh& contact_mesh, std::uint32_t triangle, const Eigen::Vector3d& b,
                                     bool front, double r, const MeshContactOptions& options,
                                     tex::BallOnRelief::Half half, std::optional<tex::BallOnRelief::Texel>* near) {
  const mesh::SurfaceFrame f = mesh::frameAt(*contact_mesh.mesh, triangle, b, mesh::FrameMode::Interpolated);
  const std::optional<tex::BallOnRelief::Touch> touch = options.ball_relief->touchOnHalf(
      {f.uv.x(), f.uv.y()}, metresPerUvAt(contact_mesh, triangle, b), r, !front, half, near ? *near : std::nullopt);
  if (!touch) return std::nullopt;
  if (near) *near = touch->texel;
  return touch->lift_m;
}

}  // namespace

double ballOnReliefLift(const ContactMesh& contact_mesh, const Eigen::Vector3d& c, double side, std::uint32_t& triangle,
                        double r, const MeshContactOptions& options, std::optional<tex::BallOnRelief::Texel>* near) {
  Eigen::Vector3d b = Eigen::Vector3d::Constant(1.0 / 3.0);
  smoothFoot(contact_mesh, c, side, triangle, b);
  return liftOnFace(contact_mesh, triangle, b, side >= 0.0, r, options, near);
}

namespace {

// A ball's lift where its foot is walked to from `triangle`; with a half, that side's relief alone.
// `near` as liftOnFace's.
std::optional<double> liftFrom(const ContactMesh& contact_mesh, const Eigen::Vector3d& c, double side,
                               std::uint32_t triangle, double r, const MeshContactOptions& options,
                               tex::BallOnRelief::Half half, std::optional<tex::BallOnRelief::Texel>* near) {
  if (half.axis < 0) return ballOnReliefLift(contact_mesh, c, side, triangle, r, options, near);
  Eigen::Vector3d b = Eigen::Vector3d::Constant(1.0 / 3.0);
  smoothFoot(contact_mesh, c, side, triangle, b);
  return liftOnFaceHalf(contact_mesh, triangle, b, side >= 0.0, r, options, half, near);
}

}  // namespace

BallReliefContacts ballOnReliefContacts(const ContactMesh& contact_mesh, const Eigen::Vector3d& c, double side,
                                        std::uint32_t triangle, const Eigen::Vector3d& b, double r,
                                        const MeshContactOptions& options, bool may_split) {
  const mesh::TexturedMesh& mesh = *contact_mesh.mesh;
  const mesh::SurfaceFrame f = mesh::frameAt(mesh, triangle, b, mesh::FrameMode::Interpolated);
  const Eigen::Vector3d n = side * f.normal;
  const Eigen::Vector2d metres_per_uv = metresPerUvAt(contact_mesh, triangle, b);
  const tex::TextureMap& map = *options.texture;
  BallReliefContacts out;
  // Each search starts from the texel the one before touched: the lifts below are read a quarter
  // texel apart, and mostly touch the same texel (BallOnRelief::touch's `near`).
  std::optional<tex::BallOnRelief::Texel> near;
  out.side[0] = {n, *liftFrom(contact_mesh, c, side, triangle, r, options, {}, &near)};
  // A quarter of the coarser texel where the texture is laid: near a pole the squeezed texels are
  // far finer, and a difference over them would read the relief's texel-scale roughness there.
  const double h = 0.25 * std::max(metres_per_uv.x() / map.width(), metres_per_uv.y() / map.height());
  if (!(h > 0.0)) return out;
  // The tangent and bitangent made orthogonal to the normal and to each other.
  const Eigen::Vector3d e1 = (f.tangent - f.tangent.dot(f.normal) * f.normal).normalized();
  const Eigen::Vector3d e2 = f.normal.cross(e1);
  // The lift rises with the heights from the front, against them from behind.
  const Eigen::Vector3d lean = side * laidLean(f, metres_per_uv, options);
  // The lift (on a half: nullopt where it holds no texel) at c and h either side of it along
  // e1 and e2, and the normal its central differences give.
  struct Lifts {
    std::optional<double> at, e1_plus, e1_minus, e2_plus, e2_minus;
    bool complete() const { return at && e1_plus && e1_minus && e2_plus && e2_minus; }
  };
  const auto liftsOf = [&](tex::BallOnRelief::Half half, bool centre) {
    Lifts l;
    if (centre) l.at = liftFrom(contact_mesh, c, side, triangle, r, options, half, &near);
    l.e1_plus = liftFrom(contact_mesh, c + h * e1, side, triangle, r, options, half, &near);
    l.e1_minus = liftFrom(contact_mesh, c - h * e1, side, triangle, r, options, half, &near);
    l.e2_plus = liftFrom(contact_mesh, c + h * e2, side, triangle, r, options, half, &near);
    l.e2_minus = liftFrom(contact_mesh, c - h * e2, side, triangle, r, options, half, &near);
    return l;
  };
  const auto normalOf = [&](const Lifts& l) {
    const double g1 = (*l.e1_plus - *l.e1_minus) / (2.0 * h);
    const double g2 = (*l.e2_plus - *l.e2_minus) / (2.0 * h);
    return clampTilt((n - g1 * e1 - g2 * e2 - lean).normalized(), n, options.max_tilt_deg);
  };
  const Lifts whole = liftsOf({}, false);
  out.side[0].normal = normalOf(whole);
  if (!options.lift_ball || options.sphere_radius_m > 0.0) return out;
  // A crease of the lift within h of the centre: its second difference along an axis is the slope's
  // jump times (h - the crease's distance from c), against curvature times h^2 where it is smooth.
  const double lift = out.side[0].lift_m;
  const double crease1 = *whole.e1_plus + *whole.e1_minus - 2.0 * lift;
  const double crease2 = *whole.e2_plus + *whole.e2_minus - 2.0 * lift;
  const int axis = crease1 >= crease2 ? 0 : 1;
  out.crease = std::max(crease1, crease2) > kCreaseSlopeJump * h;
  if (!out.crease || !may_split) return out;
  // e1 runs along u; e2 along v or against it, as the bitangent.
  const double texture_sign = axis == 0 || e2.dot(f.bitangent) >= 0.0 ? 1.0 : -1.0;
  BallReliefContacts split;
  for (int k = 0; k < 2; ++k) {
    const double towards = k == 0 ? -1.0 : 1.0;
    const Lifts on_half = liftsOf({axis, towards * texture_sign}, true);
    if (!on_half.complete()) return out;
    split.side[k] = {normalOf(on_half), *on_half.at};
  }
  split.count = 2;
  split.crease = true;
  return split;
}

Eigen::Vector3d ballOnReliefNormal(const ContactMesh& contact_mesh, const Eigen::Vector3d& c, double side,
                                   std::uint32_t triangle, const Eigen::Vector3d& b, double r,
                                   const MeshContactOptions& options) {
  return ballOnReliefContacts(contact_mesh, c, side, triangle, b, r, options, false).side[0].normal;
}

Eigen::Vector3d laidLean(const mesh::SurfaceFrame& f, const Eigen::Vector2d& metres_per_uv,
                         const MeshContactOptions& options) {
  if (options.relief_mean_slope.isZero()) return Eigen::Vector3d::Zero();
  // As the texture is laid here (slope x made-for size / local size along each axis, as the
  // haptic chart turns a normal map's slopes).
  const Eigen::Vector2d& made_for = options.normals_made_for_m;
  auto laid = [](double slope, double made_for_m, double local_m) {
    return made_for_m > 0.0 && local_m > 0.0 ? slope * made_for_m / local_m : slope;
  };
  const double su = laid(options.relief_mean_slope.x(), made_for.x(), metres_per_uv.x());
  const double sv = laid(options.relief_mean_slope.y(), made_for.y(), metres_per_uv.y());
  // The tangent and bitangent made orthogonal to the normal and to each other.
  const Eigen::Vector3d e1 = (f.tangent - f.tangent.dot(f.normal) * f.normal).normalized();
  const Eigen::Vector3d e2 = f.normal.cross(e1);
  return su * e1 + (e2.dot(f.bitangent) >= 0.0 ? sv : -sv) * e2;
}

ContactMesh::ContactMesh(const mesh::TexturedMesh& m)
    : mesh(&m), neighbours(mesh::triangleNeighbours(m)), metres_per_uv(m.positions.size(), Eigen::Vector2d::Zero()) {
  std::vector<double> weight(m.positions.size(), 0.0);
  for (const mesh::Triangle& t : m.triangles) {
    const Eigen::Vector3d e1 = m.positions[t[1]] - m.positions[t[0]], e2 = m.positions[t[2]] - m.positions[t[0]];
    const Eigen::Vector2d d1 = m.uvs[t[1]] - m.uvs[t[0]], d2 = m.uvs[t[2]] - m.uvs[t[0]];
    const double det = d1.x() * d2.y() - d2.x() * d1.y(), area = e1.cross(e2).norm();
    if (!(std::fabs(det) > 0.0) || !(area > 0.0)) continue;
    // The lengths of the position's derivatives along u and along v.
    const Eigen::Vector2d scale(((e1 * d2.y() - e2 * d1.y()) / det).norm(), ((e2 * d1.x() - e1 * d2.x()) / det).norm());
    if (!scale.allFinite()) continue;
    for (std::uint32_t v : t) metres_per_uv[v] += area * scale, weight[v] += area;
  }
  for (std::size_t v = 0; v < metres_per_uv.size(); ++v)
    metres_per_uv[v] = weight[v] > 0.0 ? Eigen::Vector2d(metres_per_uv[v] / weight[v]) : Eigen::Vector2d(1.0, 1.0);
  face_normals.reserve(m.triangles.size());
  for (std::uint32_t t = 0; t < m.triangles.size(); ++t) face_normals.push_back(mesh::faceNormal(m, t));
  std::unordered_map<mesh::PositionBits, int, mesh::PositionHash> fan;
  for (const mesh::Triangle& t : m.triangles)
    for (std::uint32_t v : t) max_hops = std::max(max_hops, 16 + ++fan[mesh::bitsOf(m.positions[v])]);
}

namespace {

// The place a smooth foot's walk has reached, as a point of the flat mesh.
Eigen::Vector3d placeOn(const mesh::TexturedMesh& mesh, std::uint32_t triangle, const Eigen::Vector3d& b) {
  const mesh::Triangle& t = mesh.triangles[triangle];
  return b[0] * mesh.positions[t[0]] + b[1] * mesh.positions[t[1]] + b[2] * mesh.positions[t[2]];
}

// Where the line through c along `dir` meets `triangle`'s plane, relative to its first corner;
// none where the line runs along the face.
std::optional<Eigen::Vector3d> meetsFacePlane(const mesh::TexturedMesh& mesh, std::uint32_t triangle,
                                              const Eigen::Vector3d& c, const Eigen::Vector3d& dir) {
  const mesh::Triangle& t = mesh.triangles[triangle];
  const Eigen::Vector3d& p0 = mesh.positions[t[0]];
  const Eigen::Vector3d face = (mesh.positions[t[1]] - p0).cross(mesh.positions[t[2]] - p0);
  const double denom = face.dot(dir);
  if (std::fabs(denom) < 1e-3 * face.norm()) return std::nullopt;
  return c - dir * (face.dot(c - p0) / denom) - p0;
}

// One round's walk of smoothFoot: from `triangle`, across edges to the triangle whose plane the
// line through c along `dir` meets inside it (or, at a border or where the line runs along a face,
// the nearest place on the last one reached); whether it found one.
bool walkAlongLine(const ContactMesh& contact_mesh, const Eigen::Vector3d& c, const Eigen::Vector3d& dir,
                   std::uint32_t& triangle, Eigen::Vector3d& barycentric) {
  const mesh::TexturedMesh& mesh = *contact_mesh.mesh;
  std::uint32_t walked = triangle;
  for (int hop = 0; hop < contact_mesh.max_hops; ++hop) {
    const std::optional<Eigen::Vector3d> meets = meetsFacePlane(mesh, walked, c, dir);
    if (!meets) return false;  // the line runs along this face: keep the last place
    const mesh::Triangle& t = mesh.triangles[walked];
    const Eigen::Vector3d& p0 = mesh.positions[t[0]];
    const Eigen::Vector3d e1 = mesh.positions[t[1]] - p0, e2 = mesh.positions[t[2]] - p0;
    const Eigen::Vector3d face = e1.cross(e2);
    const Eigen::Vector3d& w = *meets;
    const double inv = 1.0 / face.squaredNorm();
    const double l1 = w.cross(e2).dot(face) * inv, l2 = e1.cross(w).dot(face) * inv;
    const Eigen::Vector3d b(1.0 - l1 - l2, l1, l2);
    int worst = 0;
    for (int k = 1; k < 3; ++k) worst = b[k] < b[worst] ? k : worst;
    triangle = walked;
    if (b[worst] >= 0.0) {
      barycentric = b;
      return true;
    }
    barycentric = mesh::closestBarycentric(mesh, walked, w + p0);
    const std::uint32_t next = contact_mesh.neighbours[walked][std::size_t(worst)];
    if (next == mesh::kNoNeighbour) return false;
    walked = next;
  }
  return false;
}

// A foot is settled where the line along the normal there meets the surface within this (metres):
// smoothFoot's damped walk and newtonFoot alike.
constexpr double kFootSettledM = 1e-10;

// smoothFoot's last resort, where the damped walk settles nowhere: a surface curved unlike in two
// directions, a 1 mm rod under a 1 cm ball (h / R 10 round it, 0 along it), which one part alpha
// cannot settle in both (it went 0.875 of the way a round along the rod, 40 rounds short).
// Newton's method on the foot's two coordinates in the plane of the triangle it stands on: the
// undamped round's move G (where the line along the normal meets that plane, less the place) and
// its derivative, by differences of the normals' linear field over a thousandth of the triangle,
// give the place where G vanishes to first order; the walk goes there along the line from c, and
// again from the triangle it reaches. Settled as the damped walk is.
bool newtonFoot(const ContactMesh& contact_mesh, const Eigen::Vector3d& c, double side, std::uint32_t start_triangle,
                const Eigen::Vector3d& start_barycentric, std::uint32_t& triangle, Eigen::Vector3d& barycentric) {
  constexpr int kNewtonRounds = 24;
  constexpr double kDifference = 1e-3;
  const mesh::TexturedMesh& mesh = *contact_mesh.mesh;
  std::uint32_t t = start_triangle;
  Eigen::Vector3d b = start_barycentric;
  for (int round = 0; round < kNewtonRounds; ++round) {
    const mesh::Triangle& corners = mesh.triangles[t];
    const Eigen::Vector3d p0 = mesh.positions[corners[0]];
    const Eigen::Vector3d e1 = mesh.positions[corners[1]] - p0, e2 = mesh.positions[corners[2]] - p0;
    // G at barycentric (1 - l1 - l2, l1, l2), in the plane's coordinates along e1, e2 (the move
    // lies in the plane: its dot products with e1 and e2 through their Gram matrix).
    const Eigen::Matrix2d gram{{e1.dot(e1), e1.dot(e2)}, {e1.dot(e2), e2.dot(e2)}};
    const double gram_det = gram.determinant();
    if (!(std::fabs(gram_det) > 0.0)) return false;
    const auto solve2 = [](const Eigen::Matrix2d& m, double det, const Eigen::Vector2d& r) {
      return Eigen::Vector2d((m(1, 1) * r[0] - m(0, 1) * r[1]) / det, (m(0, 0) * r[1] - m(1, 0) * r[0]) / det);
    };
    const auto g = [&](const Eigen::Vector2d& l) -> std::optional<Eigen::Vector2d> {
      // frameAt takes b as given, a little outside the triangle too: the normals' linear field runs on.
      const Eigen::Vector3d n =
          side * mesh::frameAt(mesh, t, Eigen::Vector3d(1.0 - l[0] - l[1], l[0], l[1]), mesh::FrameMode::Interpolated).normal;
      const std::optional<Eigen::Vector3d> meets = meetsFacePlane(mesh, t, c, n);
      if (!meets) return std::nullopt;
      const Eigen::Vector3d move = *meets - (l[0] * e1 + l[1] * e2);
      return solve2(gram, gram_det, Eigen::Vector2d(e1.dot(move), e2.dot(move)));
    };
    const Eigen::Vector2d l(b[1], b[2]);
    const std::optional<Eigen::Vector2d> g_here = g(l);
    if (!g_here) return false;
    if ((e1 * (*g_here)[0] + e2 * (*g_here)[1]).norm() <= kFootSettledM) {
      triangle = t, barycentric = b;
      return true;
    }
    const std::optional<Eigen::Vector2d> g1 = g(l + Eigen::Vector2d(kDifference, 0.0));
    const std::optional<Eigen::Vector2d> g2 = g(l + Eigen::Vector2d(0.0, kDifference));
    if (!g1 || !g2) return false;
    Eigen::Matrix2d jacobian;
    jacobian << (*g1 - *g_here) / kDifference, (*g2 - *g_here) / kDifference;
    const double det = jacobian.determinant();
    if (!(std::fabs(det) > 1e-12)) return false;
    const Eigen::Vector2d to = l - solve2(jacobian, det, *g_here);
    const Eigen::Vector3d target = p0 + to[0] * e1 + to[1] * e2;
    walkAlongLine(contact_mesh, c, (c - target).normalized(), t, b);
  }
  return false;
}

}  // namespace

bool smoothFoot(const ContactMesh& contact_mesh, const Eigen::Vector3d& c, double side, std::uint32_t& triangle,
                Eigen::Vector3d& barycentric) {
  const mesh::TexturedMesh& mesh = *contact_mesh.mesh;
  // Fixed point: the centre's line along the interpolated normal meets the triangle's plane at
  // x; walk to the triangle that holds x; again from there (as the haptic anchor does,
  // server/textured_mesh_renderer.cpp). The place is kept consistent (a barycentric of its own
  // triangle) at every hop: beyond a box's edge the line runs along the face across it, and the
  // walk stops there. Each round moves the place by about h / R times the round before (h: c's
  // height over the surface, R: the surface's radius of curvature there), so where the surface
  // is curved twice as widely as c stands off it or more, four rounds settle it.
  constexpr int kRounds = 4;
  const std::uint32_t start_triangle = triangle;
  const Eigen::Vector3d start_barycentric = barycentric;
  bool over = false;
  std::array<double, kRounds> moved{};
  Eigen::Vector3d place = placeOn(mesh, triangle, barycentric);
  std::array<Eigen::Vector3d, 2> first_normals;  // at the start and after the first round
  for (int round = 0; round < kRounds; ++round) {
    const Eigen::Vector3d n = side * mesh::frameAt(mesh, triangle, barycentric, mesh::FrameMode::Interpolated).normal;
    if (round < 2) first_normals[std::size_t(round)] = n;
    over = walkAlongLine(contact_mesh, c, n, triangle, barycentric);
    const Eigen::Vector3d next = placeOn(mesh, triangle, barycentric);
    moved[std::size_t(round)] = (next - place).norm();
    place = next;
  }
  // Curved more tightly than c stands off it (a 1 cm ball on a 5 mm sphere: h / R about 2), the
  // rounds swing from side to side ever wider, and the place they left lay up to 40 degrees round
  // the sphere from the ball's foot (docs/physics.md, "A smooth mesh curved more tightly than the
  // object on it"). Where the last round moved more than half as far as the one before, the walk
  // starts again, each round going a part alpha of the way: a swing growing by h / R a round has
  // its fixed point at alpha = 1 / (1 + h / R), h / R read from the first rounds' growth; alpha is
  // halved whenever a round would move farther than the one before. If that settles nowhere,
  // Newton's method (newtonFoot), and failing that the undamped rounds' place, as before. Where
  // they settle nothing changes: of the physics and physics-client tests' measured lines only
  // those with h / R of 0.6 or more moved (a ball on a sphere mesh of its own radius, or on
  // another ball's cube-sphere; docs/physics.md).
  constexpr int kDampedRounds = 40;
  if (!(moved[kRounds - 1] > kFootSettledM && moved[kRounds - 1] > 0.5 * moved[kRounds - 2])) {
    // Settled. Where the foot lies on an edge or a vertex, rounding can leave the barycentric a
    // hair negative on every triangle there, and the walk ends "outside" as beyond a crease: the
    // ball was then met as past a crease for that step (32 steps of the lifted ball rolling over
    // the ridges on a flat mesh, ReliefMeshRidges.ALifted...; a 1 cm ball's centre over a 1 mm UV
    // sphere's pole). There the line along the normal meets the surface where the walk stands;
    // beyond a convex crease it meets the face's plane far off the edge the walk stopped at.
    if (over || moved[kRounds - 1] > kFootSettledM) return over;
    const Eigen::Vector3d n = side * mesh::frameAt(mesh, triangle, barycentric, mesh::FrameMode::Interpolated).normal;
    const std::optional<Eigen::Vector3d> meets = meetsFacePlane(mesh, triangle, c, n);
    return meets && (*meets + mesh.positions[mesh.triangles[triangle][0]] - place).norm() <= kFootSettledM;
  }
  // Where the first rounds already swing from one side of the curve to the other (a 1 cm ball on
  // a sphere of a quarter of a millimetre: h / R about 40), their growth reads about 1; h / R is
  // read from the curve itself too: the normal turns by the chord over R between two places of a
  // sphere.
  double growth = moved[1] > 0.0 && moved[0] > 0.0 ? moved[1] / moved[0] : 1.0;
  if (moved[0] > 0.0) {
    const double per_metre = (first_normals[1] - first_normals[0]).norm() / moved[0];
    growth = std::max(growth, (c - placeOn(mesh, start_triangle, start_barycentric)).norm() * per_metre);
  }
  double alpha = 1.0 / (1.0 + std::max(growth, 1.0));
  const std::uint32_t swung_triangle = triangle;
  const Eigen::Vector3d swung_barycentric = barycentric;
  const bool swung_over = over;
  triangle = start_triangle, barycentric = start_barycentric;
  place = placeOn(mesh, triangle, barycentric);
  bool settled = false;
  double last = std::numeric_limits<double>::infinity();
  for (int round = 0; round < kDampedRounds; ++round) {
    const Eigen::Vector3d n = side * mesh::frameAt(mesh, triangle, barycentric, mesh::FrameMode::Interpolated).normal;
    const std::optional<Eigen::Vector3d> meets = meetsFacePlane(mesh, triangle, c, n);
    if (!meets) break;
    // Where the undamped round would go.
    const Eigen::Vector3d w = *meets + mesh.positions[mesh.triangles[triangle][0]];
    const double step = (w - place).norm();
    // Here the line along the normal meets the surface where it stands: the foot, whether or not
    // the last walk ended inside a triangle (at a pole's vertex rounding leaves every fan
    // triangle's barycentric a hair negative).
    if (step <= kFootSettledM) {
      settled = true;
      break;
    }
    if (step >= last) alpha *= 0.5;
    last = step;
    const Eigen::Vector3d target = place + alpha * (w - place);
    over = walkAlongLine(contact_mesh, c, (c - target).normalized(), triangle, barycentric);
    place = placeOn(mesh, triangle, barycentric);
  }
  if (!settled && newtonFoot(contact_mesh, c, side, start_triangle, start_barycentric, triangle, barycentric)) return true;
  if (!settled) {  // no foot found either way: the rounds' place, as before
    triangle = swung_triangle, barycentric = swung_barycentric;
    return swung_over;
  }
  return true;
}

namespace {

// Where a manifold point lies on the mesh: the triangle it names on the mesh's side and the
// mesh-side point's barycentric coordinates on it; nullopt for an index out of range.
struct MeshPlace {
  std::uint32_t triangle = 0;
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
};
std::optional<MeshPlace> placeOf(const btManifoldPoint& point, bool mesh_is_b, const Eigen::Isometry3d& world_to_mesh,
                                 const mesh::TexturedMesh& mesh) {
  const int index = mesh_is_b ? point.m_index1 : point.m_index0;
  if (index < 0 || std::size_t(index) >= mesh.triangles.size()) return std::nullopt;
  const Eigen::Vector3d on_mesh = world_to_mesh * toEigen(mesh_is_b ? point.m_positionWorldOnB : point.m_positionWorldOnA);
  return MeshPlace{std::uint32_t(index), mesh::closestBarycentric(mesh, std::uint32_t(index), on_mesh)};
}

// The side of a triangle (face normal n_face) Bullet's normal says the object touches: -1 from
// behind (a bowl's inside).
double sideOf(const btManifoldPoint& point, bool mesh_is_b, const Eigen::Isometry3d& world_to_mesh,
              const Eigen::Vector3d& n_face) {
  // Bullet's normal points from B to A; towards the object it is that (mesh B) or its reverse.
  const Eigen::Vector3d towards_object = world_to_mesh.linear() * toEigen(point.m_normalWorldOnB) * (mesh_is_b ? 1.0 : -1.0);
  return n_face.dot(towards_object) < 0.0 ? -1.0 : 1.0;
}

}  // namespace

void steerChartContact(btManifoldPoint& point, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
                       const ContactMesh& contact_mesh, const btCollisionObject& other,
                       const MeshContactOptions& options, const StepContext& step) {
  if (!options.texture) return;
  const mesh::TexturedMesh& mesh = *contact_mesh.mesh;
  const Eigen::Isometry3d world_to_mesh = mesh_to_world.inverse();
  const std::optional<MeshPlace> place = placeOf(point, mesh_is_b, world_to_mesh, mesh);
  if (!place) return;
  const std::uint32_t triangle = place->triangle;
  const Eigen::Vector3d& b = place->barycentric;
  // The chart's normal at the point, towards the object: the smooth surface's, the geometry held.
  const Eigen::Vector3d n_geometric = toEigen(point.m_normalWorldOnB) * (mesh_is_b ? 1.0 : -1.0);
  const Eigen::Vector3d smooth = mesh::frameAt(mesh, triangle, b, mesh::FrameMode::Interpolated).normal;
  const double side = smooth.dot(world_to_mesh.linear() * n_geometric) < 0.0 ? -1.0 : 1.0;
  const Eigen::Vector3d n = side * meshContactNormal(mesh, triangle, b, options);
  steerContact(point, mesh_is_b, mesh_to_world.linear() * n, n_geometric, other, options.hold_height, step);
}

void leanChartContact(btManifoldPoint& point, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
                      const ContactMesh& contact_mesh, const btCollisionObject& other,
                      const MeshContactOptions& options, const StepContext& step) {
  if (options.relief_mean_slope.isZero()) return;
  const mesh::TexturedMesh& mesh = *contact_mesh.mesh;
  const Eigen::Isometry3d world_to_mesh = mesh_to_world.inverse();
  const std::optional<MeshPlace> place = placeOf(point, mesh_is_b, world_to_mesh, mesh);
  if (!place) return;
  const mesh::SurfaceFrame f = mesh::frameAt(mesh, place->triangle, place->barycentric, mesh::FrameMode::Interpolated);
  const Eigen::Vector3d lean = laidLean(f, metresPerUvAt(contact_mesh, place->triangle, place->barycentric), options);
  leanContact(point, mesh_is_b, mesh_to_world.linear(), f.normal, lean, other, options.max_tilt_deg, options.hold_height,
              step);
}

namespace {

// A ball whose centre lies over no triangle (smoothFoot): beyond a convex crease (a box's edge or
// corner) or past the mesh's border. It meets the reporting triangle's point nearest its centre,
// as Bullet found it, along the line to the centre: the edge rounds the ball's path by its radius,
// and the gap and normal go on continuously from those of the face it leaves (where the centre
// crosses the face's edge its foot is that point). On a relief, the lift of the face the ball
// leaves, blended into the face's across the edge as the line to the centre turns from one face's
// normal to the other's, so that it goes on continuously at both ends.
// Its gap, and the normal n (the line from that point to the centre); false where the centre lies
// on the surface (nothing to steer by).
bool gapPastCrease(const ContactMesh& contact_mesh, const MeshPlace& place, const Eigen::Vector3d& c, double r,
                   const MeshContactOptions& options, double& gap, Eigen::Vector3d& n) {
  const mesh::TexturedMesh& mesh = *contact_mesh.mesh;
  const Eigen::Vector3d nearest = mesh::pointAt(mesh, place.triangle, place.barycentric);
  const Eigen::Vector3d d = c - nearest;
  const double distance = d.norm();
  if (!(distance > 1e-9 * r)) return false;
  n = d / distance;
  gap = distance - r;
  if (options.texture && options.ball_relief && options.lift_ball) {
    const Eigen::Vector3d n_face = mesh::faceNormal(mesh, place.triangle);
    // The edge the point lies on (its smallest barycentric), and the face across it.
    int edge = 0;
    for (int k = 1; k < 3; ++k) edge = place.barycentric[k] < place.barycentric[edge] ? k : edge;
    const std::uint32_t across = contact_mesh.neighbours[place.triangle][std::size_t(edge)];
    const Eigen::Vector3d n_across = across != mesh::kNoNeighbour ? mesh::faceNormal(mesh, across) : n_face;
    // Both faces are met from their front where the centre lies in front of either, or level with
    // it: outside the convex crease, though behind one face's plane. By a box's upright edge a
    // ball in front of one side face lies behind the other's plane, and at a corner the face
    // across the edge the point names may be its own face's other triangle, level with the
    // centre to rounding; read from behind, those faces' grooves stood up as ridges 0.8 mm tall
    // and threw a block the pen went round.
    constexpr double kLevel = 1e-5;  // Bullet's float transforms: the level reads up to about 1e-7
    const bool front = n_face.dot(n) >= -kLevel || n_across.dot(n) >= -kLevel;
    double lift = liftOnFace(contact_mesh, place.triangle, place.barycentric, front, r, options);
    if (across != mesh::kNoNeighbour) {
      const double turned = std::acos(std::clamp(n_face.dot(n), -1.0, 1.0));
      const double to_go = std::acos(std::clamp(n_across.dot(n), -1.0, 1.0));
      if (turned + to_go > 0.0) {
        const Eigen::Vector3d b_across = mesh::closestBarycentric(mesh, across, nearest);
        const double lift_across = liftOnFace(contact_mesh, across, b_across, front, r, options);
        lift += turned / (turned + to_go) * (lift_across - lift);
      }
    }
    gap -= lift;
  }
  return true;
}

void ballPastCrease(btManifoldPoint& point, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
                    const ContactMesh& contact_mesh, const MeshPlace& place, const Eigen::Vector3d& c,
                    const ObjectBall& ball, const btCollisionObject& other, const MeshContactOptions& options,
                    const StepContext& step) {
  double gap = 0.0;
  Eigen::Vector3d n;
  if (!gapPastCrease(contact_mesh, place, c, ball.radius_m, options, gap, n)) return;
  point.m_distance1 = static_cast<btScalar>(gap);
  steerBallContact(point, mesh_is_b, mesh_to_world.linear() * n, mesh_to_world.linear() * n, ball, other,
                   options.hold_height, step);
}

}  // namespace

double ballLiftedGap(const ContactMesh& contact_mesh, const Eigen::Vector3d& c, std::uint32_t triangle, double r,
                     const MeshContactOptions& options) {
  return ballLiftedGapFrom(contact_mesh, c, triangle, r, options);
}

double ballLiftedGapFrom(const ContactMesh& contact_mesh, const Eigen::Vector3d& c, std::uint32_t& triangle, double r,
                         const MeshContactOptions& options) {
  const mesh::TexturedMesh& mesh = *contact_mesh.mesh;
  const MeshPlace reporting{triangle, mesh::closestBarycentric(mesh, triangle, c)};
  Eigen::Vector3d b = reporting.barycentric;
  if (!smoothFoot(contact_mesh, c, 1.0, triangle, b)) {  // as applyBallMeshContact meets it there
    double gap = 0.0;
    Eigen::Vector3d n;
    return gapPastCrease(contact_mesh, reporting, c, r, options, gap, n) ? gap : -r;
  }
  const mesh::SurfaceFrame smooth = mesh::frameAt(mesh, triangle, b, mesh::FrameMode::InterpolatedPhong);
  const double along = smooth.normal.dot(c - smooth.point);
  const bool front = along >= 0.0;
  double gap = std::fabs(along) - r;
  if (options.texture && options.ball_relief && options.lift_ball) gap -= liftOnFace(contact_mesh, triangle, b, front, r, options);
  return gap;
}

namespace {

// ballContactsAtFoot's reading, the foot walked to from barycentric b of `triangle`; `fallback_side`
// gives the side where the centre lies on the surface itself.
template <class FallbackSide>
std::optional<BallContactsAtFoot> ballContactsFrom(const ContactMesh& contact_mesh, std::uint32_t triangle,
                                                   Eigen::Vector3d b, const Eigen::Vector3d& c, double r,
                                                   const MeshContactOptions& options, bool may_split,
                                                   FallbackSide fallback_side) {
  const mesh::TexturedMesh& mesh = *contact_mesh.mesh;
  if (!smoothFoot(contact_mesh, c, 1.0, triangle, b)) return std::nullopt;
  const mesh::SurfaceFrame smooth = mesh::frameAt(mesh, triangle, b, mesh::FrameMode::InterpolatedPhong);
  // The side is where the centre lies from its foot, not where Bullet's normal points from the
  // reporting triangle: by a box's edge Bullet reports the face beside the one the ball stands
  // on too, its centre behind that face's plane, and that side pulled the ball into the box.
  const double along = smooth.normal.dot(c - smooth.point);
  BallContactsAtFoot out;
  out.side = along < 0.0 ? -1.0 : 1.0;
  if (along == 0.0) out.side = fallback_side();
  out.n_geometric = out.side * smooth.normal;
  out.gap_m = out.side * along - r;
  out.foot_triangle = triangle;
  if (options.texture && options.ball_relief) {
    out.contacts = ballOnReliefContacts(contact_mesh, c, out.side, triangle, b, r, options, may_split);
    // Held on the smooth surface unless lifted onto the relief (a split needs the lift).
    if (!options.lift_ball) out.contacts.side[0].lift_m = 0.0;
  } else {
    out.contacts.side[0] = {out.side * meshContactNormal(mesh, triangle, b, options), 0.0};
  }
  return out;
}

}  // namespace

std::optional<BallContactsAtFoot> ballContactsAtFoot(const btManifoldPoint& point, bool mesh_is_b,
                                                     const Eigen::Isometry3d& mesh_to_world,
                                                     const ContactMesh& contact_mesh, const ObjectBall& ball,
                                                     const MeshContactOptions& options, bool may_split) {
  const mesh::TexturedMesh& mesh = *contact_mesh.mesh;
  const Eigen::Isometry3d world_to_mesh = mesh_to_world.inverse();
  const std::optional<MeshPlace> place = placeOf(point, mesh_is_b, world_to_mesh, mesh);
  if (!place) return std::nullopt;
  return ballContactsFrom(contact_mesh, place->triangle, place->barycentric, world_to_mesh * ball.centre_world,
                          ball.radius_m, options, may_split, [&] {
                            return sideOf(point, mesh_is_b, world_to_mesh, mesh::faceNormal(mesh, place->triangle));
                          });
}

std::optional<BallContactsAtFoot> ballContactsNear(std::uint32_t triangle, const Eigen::Isometry3d& mesh_to_world,
                                                   const ContactMesh& contact_mesh, const ObjectBall& ball,
                                                   const MeshContactOptions& options, bool may_split) {
  const Eigen::Vector3d c = mesh_to_world.inverse() * ball.centre_world;
  return ballContactsFrom(contact_mesh, triangle, mesh::closestBarycentric(*contact_mesh.mesh, triangle, c), c,
                          ball.radius_m, options, may_split, [] { return 1.0; });
}

namespace {

// A ball's one contact (not split), as applyBallMeshContact writes it.
void writeOneBallContact(btManifoldPoint& point, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
                         const BallContactsAtFoot& at, const ObjectBall& ball, const btCollisionObject& other,
                         const MeshContactOptions& options, const StepContext& step) {
  const BallReliefContact& contact = at.contacts.side[0];
  // Lifted: the gap the solver holds is to the relief as the ball meets it, not to the smooth
  // surface (steerContact's rule, with that gap).
  point.m_distance1 = static_cast<btScalar>(at.gap_m - contact.lift_m);
  steerBallContact(point, mesh_is_b, mesh_to_world.linear() * contact.normal, mesh_to_world.linear() * at.n_geometric,
                   ball, other, options.hold_height, step);
}

}  // namespace

void writeBallContactAtFoot(btManifoldPoint& point, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
                            const BallContactsAtFoot& at, int k, const ObjectBall& ball, const btCollisionObject& other,
                            const MeshContactOptions& options, const StepContext& step,
                            const btPersistentManifold& manifold) {
  if (at.contacts.count == 1) return writeOneBallContact(point, mesh_is_b, mesh_to_world, at, ball, other, options, step);
  const BallReliefContact& contact = at.contacts.side[k];
  // Each side is a wall the ball meets as Bullet meets a plane, its gap taken along its normal:
  // not held at its height with the ball's sliding frozen in (steerContact's hold_height, for a
  // ball rolling over a relief), which let the ball sway across the floor of a groove at up to
  // 10 mm/s, each wall a spring that held its height and let it slide on.
  point.m_distance1 = static_cast<btScalar>((at.gap_m - contact.lift_m) * contact.normal.dot(at.n_geometric));
  steerBallContact(point, mesh_is_b, mesh_to_world.linear() * contact.normal, mesh_to_world.linear() * at.n_geometric,
                   ball, other, false, step);
  // Bullet's refresh next step recomputes a point from its local points along its normal and
  // drops one whose two ends drift apart across it: where the rewrite put it, they do not.
  point.m_localPointA = manifold.getBody0()->getWorldTransform().invXform(point.m_positionWorldOnB +
                                                                          point.m_normalWorldOnB * point.m_distance1);
  point.m_localPointB = manifold.getBody1()->getWorldTransform().invXform(point.m_positionWorldOnB);
}

namespace {

// A ball whose foot is not over the surface: past a crease (ballPastCrease).
void ballNotOverSurface(btManifoldPoint& point, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
                        const ContactMesh& contact_mesh, const ObjectBall& ball, const btCollisionObject& other,
                        const MeshContactOptions& options, const StepContext& step) {
  const Eigen::Isometry3d world_to_mesh = mesh_to_world.inverse();
  const std::optional<MeshPlace> place = placeOf(point, mesh_is_b, world_to_mesh, *contact_mesh.mesh);
  if (place)
    ballPastCrease(point, mesh_is_b, mesh_to_world, contact_mesh, *place, world_to_mesh * ball.centre_world, ball, other,
                   options, step);
}

}  // namespace

void applyBallMeshContact(btManifoldPoint& point, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
                          const ContactMesh& contact_mesh, const ObjectBall& ball, const btCollisionObject& other,
                          const MeshContactOptions& options, const StepContext& step) {
  if (!options.smooth) return;
  const std::optional<BallContactsAtFoot> at =
      ballContactsAtFoot(point, mesh_is_b, mesh_to_world, contact_mesh, ball, options, false);
  if (!at) return ballNotOverSurface(point, mesh_is_b, mesh_to_world, contact_mesh, ball, other, options, step);
  writeOneBallContact(point, mesh_is_b, mesh_to_world, *at, ball, other, options, step);
}

int creaseTagOf(const btManifoldPoint& point) {
  return int(reinterpret_cast<std::uintptr_t>(point.m_userPersistentData));
}
void setCreaseTag(btManifoldPoint& point, int tag) {
  point.m_userPersistentData = reinterpret_cast<void*>(std::uintptr_t(tag));
}

CreaseSides creaseSidesOf(const btPersistentManifold& manifold) {
  CreaseSides sides;
  for (int k = 0; k < manifold.getNumContacts(); ++k) {
    const int tag = creaseTagOf(manifold.getContactPoint(k));
    if (tag >= 1 && tag <= CreaseSides::kTags) sides.point[tag - 1] = manifold.getContactPoint(k), sides.has[tag - 1] = true;
  }
  return sides;
}

void startCreasePoint(btManifoldPoint& point, int tag, const CreaseSides* before) {
  point.m_appliedImpulse = 0;
  point.m_appliedImpulseLateral1 = 0;
  point.m_appliedImpulseLateral2 = 0;
  point.m_prevRHS = 0;
  point.m_lifeTime = 0;
  if (before && before->has[tag - 1]) {
    const btManifoldPoint& was = before->point[tag - 1];
    point.m_appliedImpulse = was.m_appliedImpulse;
    point.m_appliedImpulseLateral1 = was.m_appliedImpulseLateral1;
    point.m_appliedImpulseLateral2 = was.m_appliedImpulseLateral2;
    point.m_prevRHS = was.m_prevRHS;
    point.m_lifeTime = was.m_lifeTime;
  }
  point.m_userPersistentData = nullptr;
  setCreaseTag(point, tag);
}

void applyBallMeshManifold(btPersistentManifold& manifold, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
                           const ContactMesh& contact_mesh, const ObjectBall& ball, const btCollisionObject& other,
                           const MeshContactOptions& options, const StepContext& step, const CreaseSides* before) {
  if (!options.smooth || manifold.getNumContacts() == 0) return;
  // Every point's foot over the surface (by an edge a point past it keeps its own rule); the
  // contacts read at the first's (the others' feet are the same but for rounding).
  std::optional<BallContactsAtFoot> at;
  bool all_over = true;
  for (int k = 0; k < manifold.getNumContacts() && all_over; ++k) {
    const std::optional<BallContactsAtFoot> foot =
        k == 0 ? ballContactsAtFoot(manifold.getContactPoint(k), mesh_is_b, mesh_to_world, contact_mesh, ball, options, true)
               : std::nullopt;
    if (k == 0) at = foot;
    if (k == 0 ? !at : !ballFootIsOverSurface(manifold.getContactPoint(k), mesh_is_b, mesh_to_world, contact_mesh, ball))
      all_over = false;
  }
  if (!all_over || at->contacts.count == 1) {
    // As applyBallMeshContact rewrites each point (the first's contact is the one just read).
    for (int k = 0; k < manifold.getNumContacts(); ++k) {
      btManifoldPoint& point = manifold.getContactPoint(k);
      setCreaseTag(point, 0);
      if (k == 0 && all_over)
        writeBallContactAtFoot(point, mesh_is_b, mesh_to_world, *at, 0, ball, other, options, step, manifold);
      else
        applyBallMeshContact(point, mesh_is_b, mesh_to_world, contact_mesh, ball, other, options, step);
    }
    return;
  }
  // One point per side: those tagged keep theirs (Bullet refreshed them with points found near
  // them, or kept them), a side whose point the detection dropped (a full manifold drops one for
  // each new point) comes back as it was before it (`before`), its impulse kept for the solver's
  // warm start; a side never seen takes an untagged point (the single contact's passes its
  // impulse on) or, without one, a copy of the other side's with none. The rest go.
  bool has[2] = {false, false};
  for (int k = 0; k < manifold.getNumContacts(); ++k) {
    const int tag = creaseTagOf(manifold.getContactPoint(k));
    if (tag == 1 || tag == 2) has[tag - 1] = true;
  }
  const auto kept = [&](int side) { return before && before->has[side]; };
  for (int k = 0; k < manifold.getNumContacts(); ++k) {
    btManifoldPoint& point = manifold.getContactPoint(k);
    if (creaseTagOf(point) != 0) continue;
    const int free = !has[0] && !kept(0) ? 0 : !has[1] && !kept(1) ? 1 : -1;
    if (free >= 0) setCreaseTag(point, free + 1), has[free] = true;
  }
  bool seen[2] = {false, false};
  for (int k = manifold.getNumContacts() - 1; k >= 0; --k) {
    const int tag = creaseTagOf(manifold.getContactPoint(k));
    if ((tag == 1 || tag == 2) && !seen[tag - 1]) {
      seen[tag - 1] = true;
      continue;
    }
    manifold.removeContactPoint(k);  // untagged, or a side's second point
  }
  for (int k = 0; k < 2; ++k) {
    if (has[k] || !kept(k)) continue;
    manifold.addManifoldPoint(before->point[k]);
    has[k] = true;
  }
  for (int k = 0; k < 2; ++k) {
    if (has[k]) continue;
    btManifoldPoint added = manifold.getContactPoint(0);
    startCreasePoint(added, k + 1, nullptr);
    manifold.addManifoldPoint(added);
  }
  for (int k = 0; k < manifold.getNumContacts(); ++k) {
    btManifoldPoint& point = manifold.getContactPoint(k);
    writeBallContactAtFoot(point, mesh_is_b, mesh_to_world, *at, creaseTagOf(point) - 1, ball, other, options, step,
                           manifold);
  }
}

bool ballFootIsOverSurface(const btManifoldPoint& point, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
                           const ContactMesh& contact_mesh, const ObjectBall& ball) {
  const std::optional<MeshPlace> place = placeOf(point, mesh_is_b, mesh_to_world.inverse(), *contact_mesh.mesh);
  if (!place) return false;
  std::uint32_t triangle = place->triangle;
  Eigen::Vector3d b = place->barycentric;
  return smoothFoot(contact_mesh, mesh_to_world.inverse() * ball.centre_world, 1.0, triangle, b);
}

void applyMeshContact(btManifoldPoint& point, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
                      const ContactMesh& contact_mesh, const btCollisionObject& other,
                      const MeshContactOptions& options, const StepContext& step) {
  if (!options.smooth) return;
  const btCollisionShape* shape = other.getCollisionShape();
  if (shape->getShapeType() == SPHERE_SHAPE_PROXYTYPE) {
    // Only a ball meets the relief as a sphere: other shapes read one point.
    const ObjectBall ball{toEigen(other.getWorldTransform().getOrigin()),
                          double(static_cast<const btSphereShape*>(shape)->getRadius())};
    applyBallMeshContact(point, mesh_is_b, mesh_to_world, contact_mesh, ball, other, options, step);
    return;
  }
  const mesh::TexturedMesh& mesh = *contact_mesh.mesh;
  const Eigen::Isometry3d world_to_mesh = mesh_to_world.inverse();
  const std::optional<MeshPlace> place = placeOf(point, mesh_is_b, world_to_mesh, mesh);
  if (!place) return;
  const Eigen::Vector3d n_face = mesh::faceNormal(mesh, place->triangle);
  const double side = sideOf(point, mesh_is_b, world_to_mesh, n_face);
  const Eigen::Vector3d n = side * meshContactNormal(mesh, place->triangle, place->barycentric, options);
  steerContact(point, mesh_is_b, mesh_to_world.linear() * n, mesh_to_world.linear() * (side * n_face), other,
               options.hold_height, step);
}

}  // namespace thx::phys
