#pragma once
// A box, or a ball with a bump map, that another object meets by the texture rules (issue 29, "a
// textured object against another object"): the box seen as a mesh of its own six faces (meshes/textured_box_mesh.hpp, the
// layout its face texture is read in), met on the chart under the object as a relief mesh is
// (mesh_relief_chart.hpp, relief_collision.hpp): the box's own relief laid on its face, or, for a
// plain box, the smooth chart (its flat face, sampled over the object); each of its faces across
// an edge within the object's reach on a chart of its own (chart_boundary.hpp). So a grooved block
// on a grooved box sits in its grooves as on a grooved plane (both textures shape the contact,
// Otaduy's directional depth), a grooved block slides on a plain box as on a flat plane, and a
// ball with a bump map rests on a plain box as on a flat relief. The box moves: the chart is laid
// in its frame each step, and the object's motion relative to it decides which of a ball's
// further points Bullet may take.
//
// Which body is the ground (texturedPairGround): a box under a ball with a bump map; of two boxes,
// one of them textured, the larger (by volume; the second on a tie); of two balls with bump maps
// the larger (by radius; the second on a tie), seen as its cube-sphere (meshes/textured_ball_mesh.hpp)
// with its relief, so that both reliefs shape the pair's depth (a cube-sphere has no creases: its
// chart is not cut, relief_collision.hpp); a ball with a bump map or a
// textured box under a cylinder, the cylinder met by the rod rules of the relief plane on the chart
// laid under its axis's point nearest the ground's centre (relief_collision.cpp, meshCollision),
// its side on a convex edge with its own normal (edge_contact.hpp). Pairs without a texture keep
// their algorithms (Bullet's box-box, the scaled GJK of scaled_convex_collision.hpp). A plain ball
// or a capsule against a textured box or a ball with a bump map meets its surface as a relief
// mesh's, as balls, lifted (ball_on_object_faces.hpp): the rod rules, tried there for the capsule
// on 2026-12-04 with the chart under its centre, met the grooved block's top face at its edge when
// the pen's upright capsule pushed it and threw it at 0.22 m/s; a cylinder's flat ends are not
// balls.
#include <BulletCollision/CollisionDispatch/btCollisionConfiguration.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "clients/physics/ball_on_object_faces.hpp"
#include "clients/physics/object_ground.hpp"
#include "clients/physics/textured_box.hpp"

namespace thx::phys {

// Which of a pair's shapes the texture rules take as the ground (above).
enum class PairGround { None, First, Second };
PairGround texturedPairGround(const btCollisionShape& first, const btCollisionShape& second);

// The create function for a pair of box against sphere, box, capsule or cylinder, and of sphere
// against sphere, capsule or cylinder: the relief algorithm (relief_collision.hpp) for the pairs
// texturedPairGround takes, `otherwise` for the rest. A plain ball or a capsule against a textured
// object whose surface `catalog` holds (a textured box, a ball with a bump map) goes to
// BallOnObjectFacesAlgorithm.
struct BoxGroundCreateFunc : btCollisionAlgorithmCreateFunc {
  BoxGroundCreateFunc(btCollisionAlgorithmCreateFunc* otherwise_func, const ObjectFacesCatalog* faces_catalog)
      : otherwise(otherwise_func), catalog(faces_catalog) {}
  btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                 const btCollisionObjectWrapper* body0,
                                                 const btCollisionObjectWrapper* body1) override;
  btCollisionAlgorithmCreateFunc* otherwise;
  const ObjectFacesCatalog* catalog;
};

// The create functions of one dispatcher (they point at its configuration's); must outlive its use.
struct BoxGroundRegistration {
  ObjectFacesCatalog faces;  // the world's textured boxes and balls (PhysicsWorld::addTextured*)
  std::vector<std::unique_ptr<BoxGroundCreateFunc>> funcs;
  std::unique_ptr<btCollisionAlgorithmCreateFunc> scaled_convex;
};

// Registers BoxGroundCreateFunc for box against sphere, box, capsule and cylinder, in both orders,
// and for sphere against sphere, capsule and cylinder (a ball with a bump map's pairs without a box), each
// falling back on what the pair had: the scaled GJK where `scaled_convex` and
// usesScaledConvex say so (scaled_convex_collision.hpp), else the configuration's own.
std::unique_ptr<BoxGroundRegistration> registerBoxGroundCollision(btCollisionDispatcher& dispatcher,
                                                                  btCollisionConfiguration& configuration,
                                                                  bool scaled_convex);

}  // namespace thx::phys
