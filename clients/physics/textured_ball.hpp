#pragma once
// A moving ball with a bump map (issue 29, "a sphere with a bump map"): a relief map laid on the
// ball as meshes/textured_ball_mesh.hpp lays it (a cube projected onto the sphere, equi-angular
// faces; the visual client draws that mesh), its depth recessed along the radius. Bullet sees the
// coarse ball (a plain btSphereShape, the texture attached through the shape's user pointer and
// index). Against a relief plane both textures shape the contact as for a textured box
// (textured_box.hpp, textured_object_surface.hpp): the pair's depth at each texel of the plane
// under the ball is the plane's height minus the ball's recessed surface there; its contacts are
// found afresh each step, as every ball's are (a rolling ball's kept points inject energy:
// relief_collision.hpp). On a mesh it meets the chart under it the same way (mesh_relief_chart.hpp:
// the mesh's relief, or its smooth surface alone, standing on the mesh's bend), where a plain ball
// keeps Bullet's points, lifted (mesh_contact.hpp).
//
// On a normal-mapped plane it meets the relief the plane's normals integrate to, where a plain ball
// meets the plane (PhysicsWorld::addTexturedObjectsRelief).
//
// Against a box it meets the box's faces as a mesh's (box_ground.hpp: a plain box's smooth chart,
// a textured box's relief). A plain ball or a capsule meets its surface as a relief mesh's, lifted
// onto its relief (ball_on_object_faces.hpp: the cube-sphere, the relief met on the ball's
// curvature); another ball with a bump map or a cylinder meets it on the chart of its cube-sphere
// (box_ground.hpp: the larger of two such balls is the ground). On a plain plane it meets a smooth
// chart laid under it, as on a plain box's face (plain_plane.hpp).
#include <BulletCollision/CollisionShapes/btCollisionShape.h>

#include <Eigen/Core>

#include "clients/physics/textured_box.hpp"

namespace thx::phys {

// The ball's texture at the point of its surface in direction `p_object` from its centre (object
// frame): the recess there, and the recessed surface's outward normal (FacePoint's axis and sign
// name the cube face whose chart holds the point).
FacePoint ballTextureAt(const FaceTexture& texture, double radius_m, const Eigen::Vector3d& p_object);
// The recess alone, as ballTextureAt reads it to the bit (the raster reads it at every texel, and
// the normal only at the contacts it keeps).
double ballRecessAt(const FaceTexture& texture, double radius_m, const Eigen::Vector3d& p_object);
// The same, given the direction made unit as ballRecessAt makes it (p_object.normalized()).
double ballRecessAtUnit(const FaceTexture& texture, double radius_m, const Eigen::Vector3d& unit_direction);

// Attaches `texture` (which must outlive the shape) to a btSphereShape.
void attachBallTexture(btCollisionShape& sphere, const FaceTexture& texture);

class BallTexelGrid;
// A ball's texture with the grid of its texel centres (ball_texel_grid.hpp), by which it meets
// flat ground (ball_on_flat_ground.hpp); PhysicsWorld::addTexturedSphere lays it so. Without a
// grid (null, or a ball attached a plain FaceTexture) it meets flat ground as any other.
struct GriddedBallTexture : FaceTexture {
  const BallTexelGrid* grid = nullptr;  // must outlive the shape
};
void attachBallTexture(btCollisionShape& sphere, const GriddedBallTexture& texture);

// The texture attached to a sphere shape; nullptr for any other shape or a plain ball.
const FaceTexture* ballTextureOf(const btCollisionShape& shape);
// The grid of that texture's texel centres; nullptr where it has none.
const BallTexelGrid* ballTexelGridOf(const btCollisionShape& shape);

// Whether the shape carries an object texture: a textured box's faces or a ball's bump map.
bool hasObjectTexture(const btCollisionShape& shape);

}  // namespace thx::phys
