#pragma once
// A moving box whose faces carry a relief map (issue 29, "Textured objects"): Bullet sees the
// coarse box (a plain btBoxShape, its texture attached through the shape's user pointer and
// index: every pair Bullet knows still collides it as a box); against a relief
// plane both textures shape the contact (relief_collision.hpp), after Otaduy, Jain, Sud and Lin
// (2004): the penetration depth along the plane's normal at each texel of the plane under the box
// is the plane's relief height minus the box's surface there, the box's face pushed inwards by its
// own relief's depth. Contacts are chosen among those texels as for a plain box (the deepest, the
// spread points, each moved to the bottom of its basin: where the depth of the pair is deepest;
// the level ones on flat ground, the lowest of each quarter of the footprint), in one manifold per
// group of normals, kept between steps (relief_collision.hpp),
// and each takes the mean of the two surfaces' normals there (equal where the two surfaces touch
// at a basin's bottom, a stationary point of the pair's depth), or, where one of them has a
// crease and the other none (a crest pressing on the other body's wall), the other's
// (pair_contact_normal.hpp).
//
// Mapping: one texture on all six faces, spanning `tile_m` on each. On the face with outward
// normal along ±axis a, u grows along the object's axis (a + 1) % 3 and v along (a + 2) % 3, from
// the face's centre (u = v = 0 there); the map's normal (x along u, y along v, z out of the face)
// is carried into the object frame by (e_(a+1), e_(a+2), outward normal), which holds on either
// side since the map's normal is its depth's gradient (n = N + d_u T + d_v B for any orthonormal
// T, B and outward N).
//
// Its texture shapes contacts with a relief plane, with a mesh (on the mesh's chart under it,
// mesh_relief_chart.hpp), with the relief standing for a normal-mapped plane
// (PhysicsWorld::addTexturedObjectsRelief), with a plain plane (plain_plane.hpp: a smooth chart
// under it), and with another box, a ball with a bump map or a cylinder (box_ground.hpp: the larger
// box, or the box under the ball or the cylinder, met as a mesh of its faces); a plain ball or a
// capsule meets its faces as a relief mesh's (ball_on_object_faces.hpp);
// a normal map (no depth) given for an object is read, where objects are built, as the relief its
// normals integrate to (scene::buildObjectTexture). The visual client draws the same layout
// (meshes/textured_box_mesh.hpp).
#include <BulletCollision/CollisionShapes/btCollisionShape.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>

#include "textures/sampling.hpp"
#include "textures/texture_map.hpp"

namespace thx::phys {

struct FaceTexture {
  const tex::TextureMap* map = nullptr;  // a relief map (depth and normals); must outlive the shape
  double tile_m = 0.02;                  // metres one span of the texture covers on a face
  tex::SampleOptions sampling;           // bilinear, wrapped by default
};

// The texture at a point on the box's surface (object frame).
struct FacePoint {
  int axis = 2;                                      // the face's axis; its outward normal is sign * e_axis
  double sign = 1.0;
  double recess_m = 0.0;                             // how far the relief lies inside the face there
  Eigen::Vector3d normal_object = Eigen::Vector3d::UnitZ();  // the relief's outward normal, unit
};
// Faces tilted more than this from the plane (their outward normal's cosine with its downward
// below it) only an edge brings down: their texture is not read for contact with the plane.
inline constexpr double kSteepestTexturedFaceCos = 0.2;  // 78° from the plane

// The face is the one the point lies closest to (relative to the half extents). On an edge or a
// corner, where two or three faces meet, the one whose outward normal points most along `toward`
// (object frame; the plane's downward for a box's lowest point). A point on a face steeper than
// kSteepestTexturedFaceCos against `toward` (a side, where a slightly tilted box's vertical lines
// enter it near its bottom edge) takes the face turned most towards `toward`, read at the point's
// place over it: the bottom's grooves cut through its edge. (Read on the side, the recess was lost
// along the rim, which then reported the whole 1 mm of a grooved block's grooves as penetration
// and threw the block up.)
FacePoint faceTextureAt(const FaceTexture& texture, const Eigen::Vector3d& half_extents, const Eigen::Vector3d& p_object,
                        const Eigen::Vector3d& toward = Eigen::Vector3d::Zero());
// A point's face and where its texture lies there, read in two parts as tex::SamplePlace reads
// them: `face` carries the recess (its normal_object left at its default), faceNormal the normal,
// each as faceTextureAt reads it to the bit. The raster reads a box's depth at every texel and its
// normal only where it is a candidate.
struct FaceSample {
  FacePoint face;
  tex::SamplePlace place;
};
FaceSample faceSampleAt(const FaceTexture& texture, const Eigen::Vector3d& half_extents, const Eigen::Vector3d& p_object,
                        const Eigen::Vector3d& toward = Eigen::Vector3d::Zero());
Eigen::Vector3d faceNormal(const FaceSample& sample);

// Attaches `texture` (which must outlive the shape) to a btBoxShape. (Subclassing btBoxShape
// would emit Bullet's inline btBoxShape::getPlane here, which reads an uninitialised plane for an
// out-of-range index and fails -Werror=maybe-uninitialized.)
void attachFaceTexture(btCollisionShape& box, const FaceTexture& texture);

// The texture attached to a box shape; nullptr for any other shape or a plain box.
const FaceTexture* faceTextureOf(const btCollisionShape& shape);

// How a textured object's shape carries its texture (a box's here, a ball's: textured_ball.hpp):
// the shape's user pointer, marked by `tag` in its user index.
void attachObjectTexture(btCollisionShape& shape, const FaceTexture& texture, int tag);
const FaceTexture* objectTextureOf(const btCollisionShape& shape, int shape_type, int tag);

}  // namespace thx::phys
