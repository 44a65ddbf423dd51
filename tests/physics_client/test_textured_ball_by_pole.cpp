// A ball with a bump map let down by the pole of the bowl of bricks' uv (the floor's centre, where
// the lathe's u closes to a point) comes to rest: by a pole a relief mesh's chart is smooth
// (clients/physics/mesh_relief_chart.hpp, chartUnder), the texture having no one layout there.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "clients/physics_client/physics_scene.hpp"
#include "scenes/scene_loader.hpp"
#include "tests/support/bowl_scene.hpp"
#include "tests/support/sanitized_build.hpp"

namespace {

using thx::physclient::PhysicsScene;
using thx::physclient::SimOptions;

// A 2 cm steel ball with smooth bumps (0.15 mm high, 3.9 mm apart) and a rolling friction of
// 1e-4 m, let down 0.7 mm over the floor at (x, y) from its centre.
PhysicsScene ballAt(double x, double y) {
  char objects[400];
  std::snprintf(objects, sizeof objects,
                "objects:\n  - name: ball\n    shape: sphere\n    radius: 0.01\n    mass: 0.03\n"
                "    material: {name: steel, rolling_friction: 1.0e-4}\n    position: [%.4f, %.4f, -0.0245]\n"
                "    texture: {generator: sine, size: 256, params: {amplitude: 1.5e-4, period: 0.003927}}\n",
                x, y);
  return PhysicsScene(thx::scene::parseScene(thx::test::bowlOfBricksScene("bowl", 128, 128, objects), "bowl.yaml", "."),
                      SimOptions{});
}

// Until 2026-12-05 a chart was laid at the ball's foot there too, with the u and the tangent of
// the fan's triangle under it, which change from one triangle to the next: the ball moved at
// 1.95, 49 and 4.7 mm/s in its fourth second at the first three of these places (measured with
// the chart's pole rule switched off by hand that day). With the smooth chart but its points
// refined as on any other (not settled), it crept at 0.02 mm/s at the fourth, never asleep. Now
// it falls asleep at all six, from 0.76 to 1.01 s. The sanitizer build lets it down at the first
// place only, for two seconds.
TEST(TexturedBallByPole, ABumpyBallLetDownByTheBowlsCentreComesToRest) {
  std::vector<std::pair<double, double>> places = {{0.001, 0.0},     {0.0, 0.002},    {-0.003, 0.001},
                                                   {0.0025, -0.0025}, {-0.001, -0.0045}, {-0.002, -0.002}};
  if (thx::test::kSanitized) places.resize(1);
  const int steps = thx::test::kSanitized ? 2000 : 4000;
  for (const auto& [x, y] : places) {
    PhysicsScene scene = ballAt(x, y);
    double fastest = 0.0, asleep_from = -1.0;
    for (int k = 1; k <= steps; ++k) {
      scene.step(1e-3);
      const double v = scene.body(0).v_world.norm();
      if (k > steps - 1000) fastest = std::max(fastest, v);
      if (v > 0.0) asleep_from = -1.0;
      else if (asleep_from < 0.0) asleep_from = k * 1e-3;
    }
    std::printf("[measured] bumpy ball let down at (%.1f, %.1f) mm from the bowl's centre: fastest in its last second "
                "%.4f mm/s, asleep from %.3f s\n", x * 1e3, y * 1e3, fastest * 1e3, asleep_from);
    EXPECT_LT(fastest, 0.05e-3) << x << " " << y;
  }
}

}  // namespace
