#pragma once
// Contacts with a static textured mesh (issue 29): Bullet collides an object with the mesh's flat
// triangles (btBvhTriangleMeshShape), then each manifold point is steered as on the textured
// plane (normal_map_contact.hpp), with the normal of the surface the mesh stands for:
//  - the vertex frames interpolated at the contact (mesh::FrameMode::Interpolated: the normal
//    that shades the mesh and that the pen feels), so a ball rolls over the triangles' edges of
//    a tessellated bowl as on the smooth bowl instead of being knocked at each one;
//  - with a texture, its sampled normal turned into that frame (x along the tangent, y along the
//    bitangent: the haptic renderer's rule, server/textured_mesh_renderer.cpp), its tilt from
//    the smooth normal clamped as on the plane;
//  - for a sphere, the points moved to c - r n (Eq. 2), and with hold_height the distance set so
//    that the solver keeps the object on the flat triangle (its own normal) while the push
//    follows the steered normal.
// The triangle is the one Bullet reports in the manifold point (its index on the mesh's side:
// btConvexConcaveCollisionAlgorithm stores it as m_index0 or m_index1), the place on it the
// mesh-side point's barycentric coordinates. A ball is one contact with the smooth surface,
// whichever triangles Bullet found it on (at a vertex it touches several, and each would clamp
// the place to its own border): every point of its manifold is moved to the foot of its centre
// on the smooth surface, found by walking across the triangles' edges from Bullet's triangle,
// and its gap is measured there to Phong's surface (mesh::FrameMode::InterpolatedPhong), not to
// the flat triangle: a ball rolling fast over a tessellated sphere's convex edges would
// otherwise turn about each edge at its own radius and hop from edge to edge. On a relief, a
// ball's gap is measured further to the relief as its sphere meets it (MeshContactOptions::lift_ball),
// and where that lift has a crease under its centre (a groove's floor, two rims) it gets one
// contact for each side, each wall met as a plane (ballOnReliefContacts, applyBallMeshManifold).
// Boxes, capsules and cylinders meet a chart instead (mesh_relief_chart.hpp, relief_collision.hpp)
// unless MeshContactOptions::smooth_chart is false: their points come with the smooth surface's
// place and gap, and a normal map steers them (steerChartContact).
#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/NarrowPhaseCollision/btManifoldPoint.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

#include "clients/physics/normal_map_contact.hpp"
#include "meshes/textured_mesh.hpp"
#include "textures/sampling.hpp"
#include "textures/ball_on_relief.hpp"
#include "textures/texture_map.hpp"

namespace thx::phys {

struct MeshContactOptions {
  // nullptr: the smooth surface only. The map must outlive the world.
  const tex::TextureMap* texture = nullptr;
  tex::SampleOptions sampling;
  // The texture tile (metres per uv) the map's normals were made for; where the mesh lays the
  // texture at another scale its slopes are turned to match (as on the haptic chart). Zero: as
  // they are.
  Eigen::Vector2d normals_made_for_m = Eigen::Vector2d::Zero();
  // The relief as a ball meets it (textures/ball_on_relief.hpp), built from `texture`: with a
  // relief map, a ball's contact is steered by the relief dilated by its sphere
  // (ballOnReliefNormal) instead of the texture's normal at one point (meshContactNormal).
  // nullptr: always at one point. It must outlive the world.
  const tex::BallOnRelief* ball_relief = nullptr;
  // The slope the relief cannot hold: a normal map's mean slope (dh/du, dh/dv at the tile its
  // normals were made for; a uniformly tilted map is all mean), where `texture` and `ball_relief`
  // are the relief its normals integrate to (textures/height_from_normals.hpp), periodic and so
  // level on average. Added to a ball's lift's gradient, and the points boxes, capsules and
  // cylinders get on the relief's chart lean by it (leanChartContact). Zero for a relief map.
  Eigen::Vector2d relief_mean_slope = Eigen::Vector2d::Zero();
  // The smooth surface is a sphere of this radius (a ball with a bump map: ball_on_object_faces.hpp);
  // zero: the relief is met on its tangent plane at the ball's foot. On a sphere of radius R the
  // texels an arc d from the foot lie about d^2 / 2R below that plane (0.13 mm at the dimpled ball's
  // rims, 1.6 mm out on a 1 cm ball: half the dimples' depth). A ball of radius r from outside
  // searches the relief with its distances stretched by sqrt(1 + r/R) (exact to second order in
  // d / R at the smooth surface's height), and the point it touches is then met exactly, on its
  // own sphere (liftOnFace in mesh_contact.cpp); from inside, the stretch sqrt(1 - r/R) alone.
  double sphere_radius_m = 0.0;
  // A ball on such a relief is lifted, as on the relief plane: the gap the solver holds
  // (steerContact, with hold_height) is to the relief as its sphere meets it, so its centre rides
  // over what it cannot enter and sinks into what it can, and where its touch jumps across a
  // trough sharper than the ball it loses speed as a rigid ball rolling without slipping does (the
  // rolling-impact law, tests/physics/test_relief_mesh_ridges.cpp). false: held on the smooth
  // surface and steered by the lift's gradient only, a potential that keeps the energy (the
  // rolling model tests/physics/slope_predicted_swing.hpp integrates).
  bool lift_ball = true;
  // false: Bullet's own contact (the flat triangle's normal), for comparisons.
  bool smooth = true;
  // Without a relief, boxes, capsules and cylinders meet the smooth surface on a chart
  // (mesh_relief_chart.hpp, relief_collision.hpp), sampled `chart_grid_intervals` times (8 at
  // least) along the object's longer side; false: Bullet's points on the flat triangles, their normals steered
  // (the comparison's baseline). With a relief they always meet it on its chart.
  bool smooth_chart = true;
  int chart_grid_intervals = 16;
  double max_tilt_deg = 75.0;  // as NormalMapOptions::max_tilt_deg, from the smooth normal
  bool hold_height = true;     // as NormalMapOptions::hold_height, on the flat triangle
};

// A texture normal n_tangent (tangent space) turned into the mesh frame at frame f on `triangle`:
// its slopes rescaled to the tile laid there, its tilt from f.normal clamped (unit).
Eigen::Vector3d meshTextureNormal(const mesh::TexturedMesh& mesh, std::uint32_t triangle, const mesh::SurfaceFrame& f,
                                  Eigen::Vector3d n_tangent, const MeshContactOptions& options);

// The steering normal at barycentric b of `triangle` (mesh frame, unit, outward as the mesh is
// wound): the interpolated normal, turned by the texture's normal there if there is one (one
// point: a normal map has no depth to reach into; the plane's relief is rasterised instead,
// relief_raster.hpp; a ball on a relief mesh reads ballOnReliefNormal below).
Eigen::Vector3d meshContactNormal(const mesh::TexturedMesh& mesh, std::uint32_t triangle, const Eigen::Vector3d& b,
                                  const MeshContactOptions& options);

// A mesh with what the contacts walk on (built once; allocates).
struct ContactMesh {
  explicit ContactMesh(const mesh::TexturedMesh& m);
  const mesh::TexturedMesh* mesh;
  std::vector<mesh::Triangle> neighbours;
  // Each triangle's unit normal (mesh::faceNormal), read for every face within an object's reach
  // each step (chartBoundary: all 16,128 faces of a sphere mesh smaller than the ball on it).
  std::vector<Eigen::Vector3d> face_normals;
  // Metres per uv unit along u and v at each vertex: its triangles' (area-weighted), so that,
  // interpolated, the texture's scale does not jump at a triangle's edge (metresPerUvAt).
  std::vector<Eigen::Vector2d> metres_per_uv;
  // Edges a walk may cross: enough to go round the largest fan of triangles at one position (a
  // UV sphere's pole: Bullet may report a point on the far side of it from the ball).
  int max_hops = 16;
};

// Metres per uv unit along u and v at barycentric b of `triangle`, interpolated from its vertices.
Eigen::Vector2d metresPerUvAt(const ContactMesh& mesh, std::uint32_t triangle, const Eigen::Vector3d& b);

// The triangle and barycentric coordinates of the foot of a ball's centre c (mesh frame) on the
// smooth surface, from a triangle near it (the foot does not depend on `side`, -1 where the ball
// is behind the winding). Returns whether c lies over the surface there: false where no triangle
// holds the foot (c beyond a convex crease, such as a box's edge, or past the mesh's border), and
// then the place is the point nearest the foot on the last triangle the walk reached. Found also
// where the surface curves more tightly than c stands off it (a ball on a sphere smaller than
// itself), by a damped walk where the plain one swings ever wider, and by Newton's method where
// that settles nowhere (a thin rod: curved tightly round it and not along it).
bool smoothFoot(const ContactMesh& mesh, const Eigen::Vector3d& c, double side, std::uint32_t& triangle,
                Eigen::Vector3d& barycentric);

// A ball of radius r centred at c (mesh frame) on a relief mesh (options.ball_relief): how far the
// relief as the ball meets it lifts its centre off the smooth surface at its foot (walked to from
// `triangle`, which is updated; BallOnRelief::Touch::lift_m), the texture laid in metres there.
// `near`: a texel touched by a search nearby to start from, updated to this one's
// (BallOnRelief::touch; the lift is the same to the bit with or without it).
double ballOnReliefLift(const ContactMesh& mesh, const Eigen::Vector3d& c, double side, std::uint32_t& triangle,
                        double r, const MeshContactOptions& options,
                        std::optional<tex::BallOnRelief::Texel>* near = nullptr);
// The gap of that ball to the relief as it meets it (its distance to the smooth surface at its
// foot, less r and the lift; without a relief or with options.lift_ball false, to the smooth
// surface), the foot walked to from `triangle`; where no triangle holds the foot, the gap past a
// crease applyBallMeshContact gives there (`triangle`'s nearest point, the lift blended across
// its edge). For searching where a ball of a capsule meets the relief (ball_on_object_faces.hpp).
double ballLiftedGap(const ContactMesh& mesh, const Eigen::Vector3d& c, std::uint32_t triangle, double r,
                     const MeshContactOptions& options);
// The same, `triangle` updated to the foot's (where the walk ended): the start for a ball nearby.
double ballLiftedGapFrom(const ContactMesh& mesh, const Eigen::Vector3d& c, std::uint32_t& triangle, double r,
                         const MeshContactOptions& options);

// The steering normal of that ball (mesh frame, unit, towards the ball: side times the outward
// normal): the smooth normal tilted by the lift's gradient along the surface, taken by central
// differences of ballOnReliefLift over the ball's centre moved along the tangent and the bitangent
// (by a quarter of the coarser texel there). So the push is the gradient of one scalar, the lift:
// the read is a potential, which a texture whose scale changes under the ball (near a pole) keeps,
// and BallOnRelief's own normal, taken in the foot's one metric, does not. The ball rides the crests
// of what is narrower than it can enter and meets the full slope of what is wider.
Eigen::Vector3d ballOnReliefNormal(const ContactMesh& mesh, const Eigen::Vector3d& c, double side, std::uint32_t triangle,
                                   const Eigen::Vector3d& b, double r, const MeshContactOptions& options);

// A ball's contacts with a relief mesh (options.ball_relief) where its centre c stands over the
// surface, its foot at barycentric b of `triangle`: the normal that pushes it (ballOnReliefNormal's)
// and the lift under c. Where `may_split` and the lift has a crease within a quarter texel of c (its
// second difference over those steps, along the tangent or the bitangent, is more than
// kCreaseSlopeJump (crease_contact.hpp) times the step: a V-groove's floor, the two rims of a groove
// narrower than the ball), one contact for each side of the crease instead: the relief on that
// side of the centre alone (BallOnRelief::touchOnHalf), its lift and the normal of its own
// gradient, so the ball rests on both walls as in a wedge. One normal blended across the crease
// over a quarter texel let a ball rock from rim to rim, and a force applied at once start it up a
// wall below the wall's slope. Flat faces only (not on a ball with a bump map), lifted balls only.
struct BallReliefContact {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // mesh frame, unit, towards the ball
  double lift_m = 0.0;                                // ballOnReliefLift's (on a side: that side's)
};
struct BallReliefContacts {
  BallReliefContact side[2];  // split: [0] the side against the axis, [1] along it
  int count = 1;
  bool crease = false;  // the lift has a crease there (split where `may_split`)
};
BallReliefContacts ballOnReliefContacts(const ContactMesh& mesh, const Eigen::Vector3d& c, double side,
                                        std::uint32_t triangle, const Eigen::Vector3d& b, double r,
                                        const MeshContactOptions& options, bool may_split);

// Steers `point`, made on a smooth chart (relief_collision.hpp: its place and gap are the smooth
// surface's already), by the mesh's normal map as the plane's normal map steers a point
// (steerContact, holding the gap along the point's own normal); nothing without a texture.
void steerChartContact(btManifoldPoint& point, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
                       const ContactMesh& mesh, const btCollisionObject& other, const MeshContactOptions& options,
                       const StepContext& step = {});

// A normal map's mean slope (MeshContactOptions::relief_mean_slope) laid at frame `f`, where the
// texture's tile is `metres_per_uv` long: the slope along the surface (mesh frame, tangential;
// zero for a relief map).
Eigen::Vector3d laidLean(const mesh::SurfaceFrame& f, const Eigen::Vector2d& metres_per_uv,
                         const MeshContactOptions& options);

// Leans `point`, made on a relief's chart (relief_collision.hpp: the relief a normal map's normals
// integrate to, periodic and so level), by the map's mean slope (laidLean): its normal tilted as
// by any slope, the gap held along its own normal (steerContact with hold_height), so a box meets
// the virtual slope as on the normal-mapped plane and stays at its height. Nothing for a relief map.
void leanChartContact(btManifoldPoint& point, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
                      const ContactMesh& mesh, const btCollisionObject& other, const MeshContactOptions& options,
                      const StepContext& step = {});

// Rewrites `point` of a manifold in which the mesh is body B (`mesh_is_b`) or body A. The normal
// is oriented towards the object as Bullet found it (a bowl's inside is touched against the
// mesh's winding). A point whose triangle index is out of range is left as Bullet made it.
void applyMeshContact(btManifoldPoint& point, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
                      const ContactMesh& mesh, const btCollisionObject& other,
                      const MeshContactOptions& options, const StepContext& step = {});

// applyMeshContact's rule for a ball, for `point` made by `ball` of `other` (its sphere, or a ball
// a capsule sweeps: ball_on_object_faces.hpp): the foot of its centre on the smooth surface, the ball
// lifted onto the relief there, past a convex crease the nearest point of the reporting triangle.
void applyBallMeshContact(btManifoldPoint& point, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
                          const ContactMesh& mesh, const ObjectBall& ball, const btCollisionObject& other,
                          const MeshContactOptions& options, const StepContext& step = {});

// A ball's contacts read at the foot of one of its manifold points (`ball` made it): where its
// centre stands from the smooth surface there, and the contact (applyBallMeshContact's) or, where
// `may_split` and its lift has a crease, one for each side (ballOnReliefContacts). nullopt where
// that foot is not over the surface (past a crease: ballPastCrease) or the point's triangle is
// out of range.
struct BallContactsAtFoot {
  double side = 1.0;                                          // -1: behind the winding
  Eigen::Vector3d n_geometric = Eigen::Vector3d::UnitZ();    // the smooth surface's, towards it
  double gap_m = 0.0;                                         // to the smooth surface
  BallReliefContacts contacts;  // without a relief, the steered normal and no lift
  std::uint32_t foot_triangle = 0;
};
std::optional<BallContactsAtFoot> ballContactsAtFoot(const btManifoldPoint& point, bool mesh_is_b,
                                                     const Eigen::Isometry3d& mesh_to_world, const ContactMesh& mesh,
                                                     const ObjectBall& ball, const MeshContactOptions& options,
                                                     bool may_split);
// The same for a ball with no point of its own, its foot walked to from `triangle` (a ball in
// front of the surface where its centre lies on it).
std::optional<BallContactsAtFoot> ballContactsNear(std::uint32_t triangle, const Eigen::Isometry3d& mesh_to_world,
                                                   const ContactMesh& mesh, const ObjectBall& ball,
                                                   const MeshContactOptions& options, bool may_split);
// Whether the foot of `ball`'s centre, walked to from `point`'s triangle, is over the surface.
bool ballFootIsOverSurface(const btManifoldPoint& point, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
                           const ContactMesh& mesh, const ObjectBall& ball);
// Writes contact `k` of `at` into `point` of `manifold`: one contact as applyBallMeshContact
// writes it (held at its height); a side of a crease as Bullet meets a plane (its gap along its
// normal: held at their heights the two walls let the ball slide on into each and it swayed
// across a groove's floor at up to 10 mm/s), its local points set where the rewrite put it so
// that Bullet's refresh next step keeps it.
void writeBallContactAtFoot(btManifoldPoint& point, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
                            const BallContactsAtFoot& at, int k, const ObjectBall& ball, const btCollisionObject& other,
                            const MeshContactOptions& options, const StepContext& step,
                            const btPersistentManifold& manifold);

// Which side of a crease a point stands for: 0 none; 1 + side (BallReliefContacts::side) + 2 slot,
// slot 0 for a ball alone, 0 and 1 for a capsule's two balls split at a crease
// (ball_on_object_faces.hpp). Kept in the point's user data, the one field Bullet keeps when it
// refreshes a point with one found near it.
int creaseTagOf(const btManifoldPoint& point);
void setCreaseTag(btManifoldPoint& point, int tag);

// A manifold's crease points as they were before the detection added this step's points: a
// full manifold drops one of its points for each new one, and a side's point dropped that way
// comes back with the impulse it carried.
struct CreaseSides {
  static constexpr int kTags = 4;
  btManifoldPoint point[kTags];  // by tag - 1
  bool has[kTags] = {false, false, false, false};
};
CreaseSides creaseSidesOf(const btPersistentManifold& manifold);
// Makes `point` (a copy of another) a new crease point `tag`: the impulses it carried before
// (`before`, nullptr: none) for the solver's warm start, or none.
void startCreasePoint(btManifoldPoint& point, int tag, const CreaseSides* before);

// A ball's whole manifold with a relief mesh (`ball` of `other`, a sphere): every point as
// applyBallMeshContact rewrites it, except where every point's foot stands over the surface and
// ballOnReliefContacts splits the contact at a crease: then one point for each side (tags 1 and
// 2), the others removed, a side missing brought back from `before` (creaseSidesOf before this
// step's detection; nullptr: none) or added. The manifold's body 1 is the mesh where `mesh_is_b`.
void applyBallMeshManifold(btPersistentManifold& manifold, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
                           const ContactMesh& mesh, const ObjectBall& ball, const btCollisionObject& other,
                           const MeshContactOptions& options, const StepContext& step = {},
                           const CreaseSides* before = nullptr);

}  // namespace thx::phys
