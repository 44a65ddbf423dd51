// A box whose texture file holds normals only (issue 29, "a box whose faces have a normal or
// relief map"): its faces meet the relief those normals integrate to (scene::buildObjectTexture),
// so the shipped grooved block with its grooves given as a normal map rests in the plane's grooves
// as the one given as a relief does.
#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "clients/physics/textured_world.hpp"
#include "clients/physics_client/physics_scene.hpp"
#include "scenes/scene_loader.hpp"
#include "tests/support/process.hpp"
#include "tests/support/block_grooves.hpp"
#include "tests/support/temp_dir.hpp"
#include "textures/texture_io.hpp"

namespace test_normal_mapped_box {

namespace {

using thx::physclient::BodyState;
using thx::physclient::PhysicsScene;
namespace tex = thx::tex;

const std::string kBlockTexture =
    "texture: {generator: grooves, size: 64, params: {period: 0.004, width: 0.004, depth: 0.0008}}";

// The shipped grooved block's scene, the block's texture replaced by `texture` (a scene field).
thx::scene::Scene groovedBlock(const std::string& texture) {
  std::string text = thx::test::slurp(std::string(THX_SOURCE_DIR) + "/scenes/grooved_block.yaml");
  const std::size_t at = text.find(kBlockTexture);
  if (at == std::string::npos) throw std::runtime_error("grooved_block.yaml: the block's texture line moved");
  text.replace(at, kBlockTexture.size(), texture);
  return thx::scene::parseScene(text, "grooved_block.yaml", ".");
}

// The block's state after `rest_s` of physics with no pen in the scene's way, then `push_s` pushed
// along +y (the grooves) by half its weight at its centre.
BodyState settle(const thx::scene::Scene& scene, double rest_s, double push_s) {
  PhysicsScene s(scene);
  const double dt = 1.0 / scene.rates.physics_hz;
  for (int k = 0; k < int(std::lround(rest_s / dt)); ++k) s.step(dt);
  btRigidBody* block = nullptr;  // the scene's object 0 (physics-client's bodies carry their scene index)
  const btCollisionObjectArray& bodies = s.world().world().getCollisionObjectArray();
  for (int i = 0; i < bodies.size(); ++i)
    if (bodies[i]->getUserIndex() == 0 && !bodies[i]->isStaticOrKinematicObject()) block = btRigidBody::upcast(bodies[i]);
  if (!block) throw std::runtime_error("no block in the scene");
  const double weight = scene.objects[0].mass_kg * 9.81;
  for (int k = 0; k < int(std::lround(push_s / dt)); ++k) {
    block->activate(true);
    block->applyCentralForce(btVector3(0.0, btScalar(0.5 * weight), 0.0));
    s.step(dt);
  }
  return s.bodies().at(0);
}

}  // namespace

TEST(NormalMappedBox, RestsAndSlidesInTheGroovesAsTheSameGroovesGivenAsARelief) {
  const thx::test::TempDir dir("thx_normal_mapped_box");
  // The block's grooves as the scene generates them (extent = the 2 cm tile), made a relief whose
  // normals are its heights' central differences (the project's rule, which the integration
  // inverts), written once whole and once as its normals only.
  const tex::TextureMap relief = thx::test::centralDifferenceBlockGrooves(tex::Representation::Relief);
  const std::string relief_file = dir.file("block_relief.png");
  const std::string normals_file = dir.file("block_normals.png");
  tex::saveTexture(relief_file, relief);
  tex::saveTexture(normals_file, thx::test::centralDifferenceBlockGrooves(tex::Representation::Normal));

  const thx::scene::Scene as_relief = groovedBlock("texture: {file: " + relief_file + "}");
  const thx::scene::Scene as_normals = groovedBlock("texture: {file: " + normals_file + "}");
  EXPECT_TRUE(PhysicsScene(as_normals).warnings().empty());  // grooves are level on average
  // At rest, then pushed along the grooves by half its weight for 0.2 s (it slides at (0.5 - 0.3) g).
  const double rest_s = 0.4, push_s = 0.2;
  const BodyState a = settle(as_relief, rest_s, 0.0), b = settle(as_normals, rest_s, 0.0);
  const BodyState pa = settle(as_relief, rest_s, push_s), pb = settle(as_normals, rest_s, push_s);
  std::printf("[measured] grooved block at rest after %.1f s: z %.4f mm (relief) and %.4f mm (normals), %.3f um "
              "apart; pushed along the grooves: moved %.3f and %.3f mm along y, %.3f um apart\n",
              rest_s, a.p_world.z() * 1e3, b.p_world.z() * 1e3, (a.p_world - b.p_world).norm() * 1e6,
              (pa.p_world.y() - a.p_world.y()) * 1e3, (pb.p_world.y() - b.p_world.y()) * 1e3,
              (pa.p_world - pb.p_world).norm() * 1e6);
  // In its grooves (0.8 mm lower than on the rims, where its centre would be half its height up).
  EXPECT_LT(b.p_world.z(), 0.5 * as_normals.objects[0].size_m.z() - 0.5 * 0.0008);
  EXPECT_LT(b.v_world.norm(), 1e-3);
  // The same as the relief to a few micrometres: the integration returns the depths to 16 bits.
  EXPECT_LT((a.p_world - b.p_world).norm(), 5e-6);
  EXPECT_GT(pb.p_world.y() - b.p_world.y(), 0.02);  // it slides along ...
  EXPECT_LT((pa.p_world - pb.p_world).norm(), 1e-4);  // 0.3 % of the slide
}

}  // namespace test_normal_mapped_box
