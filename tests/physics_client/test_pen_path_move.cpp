// physics-client --pen-script follows a script's move steps (issue 30, docs/scenes.md
// "device.script"): straight from where the pen is to the move's point, its height above the
// plane; a hold after a move keeps the pen there, off the surface.
#include <gtest/gtest.h>

#include "clients/physics_client/pen_path.hpp"
#include "clients/physics_client/physics_scene.hpp"
#include "scenes/scene_loader.hpp"

namespace test_pen_path_move {

using namespace thx::physclient;

TEST(PenPathMove, ThePenFollowsAMoveOffTheSurfaceAndStaysThere) {
  const thx::scene::Scene scene = thx::scene::parseScene(
      "version: 1\nname: lift\nsurface:\n  size: [0.2, 0.2]\n  texture: {generator: bricks, size: 64}\n"
      "device:\n  script:\n    - press: {position: [0.0, 0.0], force: 1, duration: 0.2}\n"
      "    - move: {to: [0.01, 0.0, 0.02], duration: 0.5}\n    - hold: {duration: 0.5}\n",
      "lift.yaml", "");
  PhysicsScene sim(scene, SimOptions{});
  const PenPath path(penPathFromScript(sim, 1e-3));
  const double surface_z = sim.surface().at(0.0, 0.0).height_m;
  EXPECT_NEAR((path.at(0.1) - Eigen::Vector3d(0.0, 0.0, surface_z)).norm(), 0.0, 1e-12);  // pressing
  // Half way through the move: half way from the surface point to the move's.
  const Eigen::Vector3d half = 0.5 * (Eigen::Vector3d(0.0, 0.0, surface_z) + Eigen::Vector3d(0.01, 0.0, 0.02));
  EXPECT_NEAR((path.at(0.45) - half).norm(), 0.0, 1e-9);
  // The hold keeps it in the air, and so does the end.
  EXPECT_NEAR((path.at(0.9) - Eigen::Vector3d(0.01, 0.0, 0.02)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((path.at(5.0) - Eigen::Vector3d(0.01, 0.0, 0.02)).norm(), 0.0, 1e-12);
}

}  // namespace test_pen_path_move
