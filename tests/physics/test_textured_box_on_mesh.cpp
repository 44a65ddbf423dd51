// A grooved block on a grooved curved mesh (issue 29, "Textured objects" on a textured mesh;
// clients/physics/mesh_relief_chart.hpp): the V-grooves of grooved_block_scene.hpp laid on the
// inside of a horizontal pipe (a trough of radius 10 cm, its grooves along the pipe's axis) and on
// the block's faces. Both reliefs shape the contact on the chart under the block, standing on the
// pipe's bend: the block settles into the grooves, slides along them and not across them. A plain
// block rides the ridges' tops, and across the pipe its corners meet the ridges the bend raises
// (test_plain_objects_on_relief_mesh.cpp has the plain objects). A flat mesh gives the relief
// plane's answer.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "clients/physics/relief_collision.hpp"
#include "tests/physics/grooved_block_scene.hpp"

namespace thx::phys::test::test_textured_box_on_mesh {
namespace {

using namespace grooved_block;

struct MeshScene {
  mesh::GeneratedMesh surface;
  tex::TextureMap map, block_map;
  std::unique_ptr<PhysicsWorld> world;
  btRigidBody* block = nullptr;
  Eigen::Vector3d bottom = Eigen::Vector3d::Zero();  // the surface's lowest point under the block

  // trough: the inside of a pipe along y, its lowest line at z = 0; else the top of a flat slab
  // at z = 0. Both laid with one texture tile per 4 cm (the pipe's adjusted to whole tiles round).
  MeshScene(bool trough, bool textured, int settle_steps = 500)
      : surface(groovedGround(trough)),
        map(heightMap(128, kExtent, vGrooves)),
        block_map(heightMap(128, kExtent, vGrooves)),
        world(std::make_unique<PhysicsWorld>()) {
    bottom = addGroovedGround(*world, surface, trough, map);
    // The block's ridges over the surface's floors (half a period from its ridges, which lie at
    // x = k P on both surfaces), a little above where they fit.
    const Eigen::Isometry3d start = at(0.5 * kPeriod, bottom.y(), kHalf.z() - (textured ? kDepth : 0.0) + 2e-4);
    FaceTexture faces;
    faces.map = &block_map;
    faces.tile_m = kExtent;
    block = textured ? &world->addTexturedBox(kHalf, kMass, start, {kFriction, 0.0, 0.0}, faces)
                     : &world->addBox(kHalf, kMass, start, {kFriction, 0.0, 0.0});
    for (int k = 0; k < settle_steps; ++k) world->step(kDt);  // settle into the grooves
  }

  Eigen::Vector3d push(const Eigen::Vector3d& force_over_weight, double seconds) {
    return pushBlock(*world, *block, force_over_weight, seconds);
  }
};

TEST(TexturedBoxOnMesh, TheRuleTakesATexturedBoxOnAReliefMesh) {
  MeshScene scene(true, true, 0);
  const btCollisionShape& mesh_shape = *scene.world->world().getCollisionObjectArray()[0]->getCollisionShape();
  ASSERT_NE(meshReliefOf(mesh_shape), nullptr);
  EXPECT_TRUE(reliefTakesMeshPair(*scene.block->getCollisionShape(), mesh_shape));
}

TEST(TexturedBoxOnMesh, OnAFlatMeshTheBlockSitsInTheGroovesAsOnTheReliefPlane) {
  MeshScene textured(false, true), plain(false, false);
  Scene on_plane(true, false);
  // The textured block sinks by the grooves' depth, as on the relief plane (its x settles into
  // whichever groove the mesh's uv puts under it).
  EXPECT_NEAR(positionOf(*textured.block).z(), positionOf(*on_plane.block).z(), 2e-5);
  EXPECT_NEAR(positionOf(*textured.block).z(), kHalf.z() - kDepth, 1.6e-4);
  EXPECT_NEAR(positionOf(*plain.block).z(), kHalf.z(), 1.6e-4);
}

TEST(TexturedBoxOnMesh, InAGroovedTroughTheBlockSitsInTheGroovesAndStaysThere) {
  MeshScene textured(true, true), plain(true, false);
  const Eigen::Vector3d rest = positionOf(*textured.block);
  const Eigen::Vector3d moved = textured.push(Eigen::Vector3d::Zero(), 1.0);
  EXPECT_LT(moved.norm(), 1e-5) << moved.transpose();
  EXPECT_LT(toEigen(textured.block->getLinearVelocity()).norm(), 1e-3);
  // Lower than the plain block by most of the grooves' depth, its ridges in the pipe's floors
  // (0.85 mm measured: set half a period off the bottom line, its ridges meet the rising sides
  // unevenly, 0.49 mm up at 10 mm and 0.18 mm at 6 mm); not through the pipe's bend (read on the
  // flat tangent plane it sank 1.30 mm).
  const double sink = positionOf(*plain.block).z() - rest.z();
  RecordProperty("sink_um", int(std::lround(sink * 1e6)));
  EXPECT_GT(sink, 0.6 * kDepth) << rest.transpose() << " / " << positionOf(*plain.block).transpose();
  EXPECT_LT(sink, 1.1 * kDepth) << rest.transpose() << " / " << positionOf(*plain.block).transpose();
  EXPECT_LT(std::fabs(rest.x()), kPeriod) << rest.transpose();
  const Eigen::Vector3d up = toEigen(textured.block->getWorldTransform().getBasis().getColumn(2));
  EXPECT_GT(up.z(), std::cos(deg(2.0)));
}

TEST(TexturedBoxOnMesh, InAGroovedTroughTheBlockSlidesAlongTheGroovesAndNotAcrossThem) {
  MeshScene along(true, true), across(true, true), plain_across(true, false);
  const Eigen::Vector3d a = along.push({0.0, 0.5, 0.0}, 0.2);
  const Eigen::Vector3d c = across.push({0.5, 0.0, 0.0}, 0.2);
  const Eigen::Vector3d p = plain_across.push({0.5, 0.0, 0.0}, 0.2);
  RecordProperty("along_um", int(std::lround(a.y() * 1e6)));
  RecordProperty("along_sideways_um", int(std::lround(a.x() * 1e6)));
  RecordProperty("across_um", int(std::lround(c.norm() * 1e6)));
  RecordProperty("plain_across_um", int(std::lround(p.x() * 1e6)));
  // Along the pipe's axis the grooves are straight: (0.5 - 0.3) g for 0.2 s is 39 mm.
  EXPECT_NEAR(a.y(), 0.5 * (0.5 - 0.3) * kG * 0.04, 0.1 * 0.0392) << a.transpose();
  EXPECT_LT(std::fabs(a.x()), 3e-4) << a.transpose();
  // Across, the grooves' walls hold it. The plain block rests on the two ridges 8 mm either side
  // of the bottom line (0.31 mm up the bend) and its corner meets the wall of the ridge 12 mm out
  // (0.71 mm up) within half a period: held too, where it slid up the pipe's side on Bullet's
  // smooth triangles before plain objects met the relief (2026-12-02).
  EXPECT_LT(c.norm(), 0.25 * kPeriod) << c.transpose();
  EXPECT_LT(std::fabs(p.x()), 0.5 * kPeriod) << p.transpose();
}

}  // namespace
}  // namespace thx::phys::test::test_textured_box_on_mesh
