// A ball rolling off a mesh's convex edge (mesh_contact.hpp, ballPastCrease): a 5 mm ball rolling at
// 0.1 m/s along a groove of the grooved slab (grooved_block_scene.hpp's flat box mesh, its top at
// z = 0, its edge at y = 0.1 m) rolls over the edge and falls, as off Bullet's own box; and so off
// a textured box of the slab's size with the grooves on its faces, whose faces a plain ball meets
// as a relief mesh's (ball_on_object_faces.hpp; before, it met the coarse box and rode the ridges). Before a
// ball's side was taken from its foot, Bullet's point on the face beside the top (the ball's centre
// behind that face's plane) read as a ball touched from behind: on the untextured slab the ball
// stopped 1.3 mm short of the edge, kicked up and down at up to 0.77 m/s; on the grooved slab it
// was pulled down into the slab at 2.1 m/s and rattled about inside it.
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "clients/physics/ball_on_object_faces.hpp"
#include "tests/physics/grooved_block_scene.hpp"
#include "textures/ball_on_relief.hpp"

namespace thx::phys::test::test_ball_off_an_edge {
namespace {

using namespace grooved_block;

constexpr double kRadius = 0.005, kSpeed = 0.1, kEdgeY = 0.1;

enum class Ground { BulletBox, SmoothMesh, GroovedMesh, GroovedBox };

struct Fall {
  double y = 0.0, z = 0.0;       // the centre at the end
  double speed_y = 0.0;          // its speed along the roll at the end
  double fastest_up = 0.0;       // the largest upward speed on the way
  bool ever_inside = false;      // the centre ever inside the slab
  double settled_z = 0.0;        // the centre's height before the launch
};

Fall rollOff(Ground ground, double seconds) {
  const tex::TextureMap map = heightMap(128, kExtent, vGrooves);
  const tex::BallOnRelief ball_relief(map, tex::Address::Wrap);
  const mesh::GeneratedMesh slab = groovedGround(false);  // 0.2 x 0.2 x 0.02 m, its top at z = 0 below
  PhysicsWorld world;
  const BodyMaterial ground_material{1.0, 0.0, 0.0};
  if (ground == Ground::BulletBox) {
    world.addBox(Eigen::Vector3d(0.1, 0.1, 0.01), 0.0, at(0.0, 0.0, -0.01), ground_material);
  } else if (ground == Ground::GroovedBox) {
    FaceTexture faces;  // on the top face u runs along x from its centre, as on the mesh
    faces.map = &map;
    faces.tile_m = kExtent;
    world.addTexturedBox(Eigen::Vector3d(0.1, 0.1, 0.01), 0.0, at(0.0, 0.0, -0.01), ground_material, faces);
  } else {
    MeshContactOptions options;
    if (ground == Ground::GroovedMesh) {
      options.texture = &map;
      options.normals_made_for_m = Eigen::Vector2d::Constant(kExtent);
      options.ball_relief = &ball_relief;  // lifted, the default
    }
    world.addTexturedMesh(slab.mesh, at(0.0, 0.0, -0.01), ground_material, options);
  }
  // In a groove's floor (x = P / 2), 3 cm short of the edge.
  btRigidBody& ball = world.addSphere(kRadius, 0.004, at(0.5 * kPeriod, kEdgeY - 0.03, kRadius + 1e-4), {0.3, 0.0, 0.0});
  for (int k = 0; k < 100; ++k) world.step(kDt);  // settle
  Fall fall;
  fall.settled_z = positionOf(ball).z();
  ball.setLinearVelocity(btVector3(0.0, btScalar(kSpeed), 0.0));
  ball.setAngularVelocity(btVector3(btScalar(-kSpeed / kRadius), 0.0, 0.0));  // rolling
  for (int k = 0; k < int(std::lround(seconds / kDt)); ++k) {
    world.step(kDt);
    const Eigen::Vector3d c = positionOf(ball);
    fall.fastest_up = std::max(fall.fastest_up, double(ball.getLinearVelocity().z()));
    fall.ever_inside = fall.ever_inside || (std::fabs(c.x()) < 0.1 && std::fabs(c.y()) < 0.1 && c.z() < 0.0 && c.z() > -0.02);
  }
  const Eigen::Vector3d c = positionOf(ball);
  fall.y = c.y();
  fall.z = c.z();
  fall.speed_y = double(ball.getLinearVelocity().y());
  return fall;
}

TEST(BallOffAnEdge, RollsOverAMeshsEdgeAndFallsAsOffBulletsBox) {
  const double seconds = 0.6;  // it reaches the edge at about 0.3 s
  const Fall box = rollOff(Ground::BulletBox, seconds);
  const Fall smooth = rollOff(Ground::SmoothMesh, seconds);
  const Fall grooved = rollOff(Ground::GroovedMesh, seconds);
  const Fall grooved_box = rollOff(Ground::GroovedBox, seconds);
  for (const auto& [name, f] : {std::pair{"Bullet's box", box}, {"smooth mesh", smooth}, {"grooved mesh", grooved},
                                {"grooved box", grooved_box}}) {
    std::printf("[measured] %s: settled at z = %.2f um; at %.1f s the centre at y = %.4f m, z = %.4f m, %.4f m/s along; "
                "fastest up %.4f m/s%s\n",
                name, f.settled_z * 1e6, seconds, f.y, f.z, f.speed_y, f.fastest_up, f.ever_inside ? "; inside the slab" : "");
    EXPECT_GT(f.y, kEdgeY) << name;
    EXPECT_LT(f.z, -0.1) << name << ": it has fallen";
    EXPECT_FALSE(f.ever_inside) << name;
    EXPECT_LT(f.fastest_up, 0.02) << name << ": no kick at the edge";
  }
  // The smooth mesh's edge is the box's edge: the ball leaves it with the box's speed.
  EXPECT_NEAR(smooth.speed_y, box.speed_y, 0.05 * box.speed_y);
  EXPECT_NEAR(smooth.y, box.y, 0.005);
  // In the groove the ball rests on the two ridges either side (its contacts 2.2 mm out on the
  // walls would lie past them), its centre sqrt(r^2 - (P/2)^2) above their top (4.583 mm), as far
  // on the textured box as on the grooved mesh.
  EXPECT_NEAR(grooved.settled_z, std::sqrt(kRadius * kRadius - 0.25 * kPeriod * kPeriod), 10e-6);
  EXPECT_NEAR(grooved_box.settled_z, grooved.settled_z, 0.1e-6);
}

// A ball beside a box's upright edge, level with its top, touches nothing: its point on the top
// face's triangle that holds the corner (the corner nearest) is read from the front whether the
// centre lies a rounding above or below the top's plane, and from the front too where the centre
// lies behind the other side face's plane (in front of this one). Before, a centre 1e-10 m below
// the top, as Bullet's float transforms leave it, read the top's V-grooves from behind: ridges
// 1 mm tall, a gap of -0.7 mm, and the pen going round the grooved block in its scene kicked it
// 0.4 mm.
TEST(BallOffAnEdge, ABallBesideABoxsCornerLevelWithItsTopReadsTheReliefFromTheFront) {
  const tex::TextureMap map = heightMap(128, kExtent, vGrooves);
  FaceTexture texture;
  texture.map = &map;
  texture.tile_m = kExtent;
  const Eigen::Vector3d half(0.01, 0.01, 0.005);
  const std::unique_ptr<ObjectFaces> box_faces = boxFaces(half, texture);
  ObjectFaces& faces = *box_faces;
  faces.options.hold_height = false;  // the gap as it is found
  constexpr double r = 0.004;
  btSphereShape shape{btScalar(r)};
  btCollisionObject object;
  object.setCollisionShape(&shape);
  for (const double below : {-1e-10, 0.0, 1e-10}) {
    // 1.2 mm in from the -x side, 0.13 mm off the -y face: nearest the corner (-x, -y, top) on
    // the top triangle that does not hold the -y edge there.
    const Eigen::Vector3d c(-half.x() + 0.0012, -half.y() - r - 1.3e-4, half.z() - below);
    int checked = 0;
    for (std::uint32_t t = 0; t < std::uint32_t(faces.mesh.triangles.size()); ++t) {
      const Eigen::Vector3d n_face = mesh::faceNormal(faces.mesh, t);
      const Eigen::Vector3d q = mesh::pointAt(faces.mesh, t, mesh::closestBarycentric(faces.mesh, t, c));
      if (n_face.z() < 0.5 || (q - Eigen::Vector3d(-half.x(), -half.y(), half.z())).norm() > 1e-12) continue;
      btManifoldPoint point(btVector3(0, 0, 0), btVector3(0, 0, 0), toBt(Eigen::Vector3d((c - q).normalized())),
                            btScalar((c - q).norm() - r));
      point.m_index1 = int(t);
      point.m_positionWorldOnB = toBt(q);
      object.setWorldTransform(toBt(at(c.x(), c.y(), c.z())));
      applyBallMeshContact(point, true, Eigen::Isometry3d::Identity(), faces.contact, ObjectBall{c, r}, object,
                           faces.options);
      std::printf("[measured] centre %+.0e m off the top's plane, beside the corner: gap %.3f mm (distance less r %.3f)\n",
                  -below, double(point.m_distance1) * 1e3, ((c - q).norm() - r) * 1e3);
      EXPECT_GT(double(point.m_distance1), 0.1e-3);
      ++checked;
    }
    EXPECT_EQ(checked, 1);
  }
}

}  // namespace
}  // namespace thx::phys::test::test_ball_off_an_edge
