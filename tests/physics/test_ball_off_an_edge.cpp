// A ball rolling off a mesh's convex edge (mesh_contact.hpp, ballPastCrease): a 5 mm ball rolling at
// 0.1 m/s along a groove of the grooved slab (grooved_block_scene.hpp's flat box mesh, its top at
// z = 0, its edge at y = 0.1 m) rolls over the edge and falls, as off Bullet's own box; and so off
// a textured box of the slab's size with the grooves on its faces, whose faces a plain ball meets
// as a relief mesh's (ball_on_box_faces.hpp; before, it met the coarse box and rode the ridges). Before a
// ball's side was taken from its foot, Bullet's point on the face beside the top (the ball's centre
// behind that face's plane) read as a ball touched from behind: on the untextured slab the ball
// stopped 1.3 mm short of the edge, kicked up and down at up to 0.77 m/s; on the grooved slab it
// was pulled down into the slab at 2.1 m/s and rattled about inside it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

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

}  // namespace
}  // namespace thx::phys::test::test_ball_off_an_edge
