// The texel paths of surface contacts are fit for the paper's Eq. 5: a ball rolling several
// texels per step reports every texel it crosses (4-neighbours in order, none skipped), each with
// the texel's own normal (nearest, not bilinear), its entry time, and the ball's mass.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "clients/physics_client/lcm_io.hpp"
#include "clients/physics_client/physics_scene.hpp"
#include "scenes/scene_loader.hpp"
#include "thx_msgs/protocol.hpp"

namespace test_texel_path {

namespace {

using namespace thx::physclient;

// An egg-crate normal map (0.78 mm texels, slopes up to 1.8°) and a 5 mm ball launched at 3.3 m/s
// diagonally: ~4 columns and ~2 rows per 1 ms step.
const std::string kScene = R"(version: 1
name: fast_ball
surface:
  size: [0.4, 0.4]
  texture: {generator: sine, size: 512, params: {extent: 0.4, amplitude: 0.00005, period: 0.01}}
  representation: normal
  material: wood
objects:
  - name: ball
    shape: sphere
    radius: 0.005
    mass: 0.004
    material: steel
    position: [-0.15, -0.08, 0.005]
    velocity: [3.0, 1.4, 0.0]
rates: {physics_hz: 1000}
)";

struct Recorded {
  std::vector<Texel> path;
  std::vector<double> mass;
  int steps_touching = 0;
  std::size_t most_in_one_step = 0;
};

Recorded run(PhysicsScene& sim, int steps) {
  Recorded r;
  for (int k = 0; k < steps; ++k) {
    sim.step(1e-3);
    for (const LastingContact& c : sim.takeContacts()) {
      if (c.body_a != 0 || c.body_b != kBodySurface) continue;
      ++r.steps_touching;
      r.most_in_one_step = std::max(r.most_in_one_step, c.path.size());
      r.path.insert(r.path.end(), c.path.begin(), c.path.end());
      r.mass.push_back(c.mass_a_kg);
      EXPECT_EQ(c.path_dropped, 0);
    }
  }
  return r;
}

TEST(TexelPath, FastBallRecordsEveryTexelCrossedWithTheNearestNormal) {
  const thx::scene::Scene scene = thx::scene::parseScene(kScene, "fast_ball.yaml", ".");
  SimOptions options;
  options.pen.shape = PenShape::None;
  PhysicsScene sim(scene, options);
  const thx::tex::TexturedSurface& s = sim.surface();
  const Recorded r = run(sim, 60);
  ASSERT_GT(r.steps_touching, 50);
  EXPECT_GE(r.most_in_one_step, 5u);  // several texels per step: one texel per step would skip
  ASSERT_GT(r.path.size(), 250u);
  for (double m : r.mass) EXPECT_DOUBLE_EQ(m, 0.004);

  // Every texel crossed: consecutive entries are 4-neighbours, times increase within the run.
  for (std::size_t k = 1; k < r.path.size(); ++k) {
    const Texel &a = r.path[k - 1], &b = r.path[k];
    ASSERT_EQ(std::llabs(b.i - a.i) + std::llabs(b.j - a.j), 1) << "texel " << k << " skips";
    EXPECT_GE(b.t_s, a.t_s);
  }
  // It ends where the ball is: the texel under its centre.
  const Eigen::Vector3d c = s.toLocal(sim.body(0).p_world);
  long long ei = 0, ej = 0;
  s.texelContaining(c.x(), c.y(), ei, ej);
  EXPECT_EQ(r.path.back().i, ei);
  EXPECT_EQ(r.path.back().j, ej);

  // Normals: the map's own texel (nearest), not the bilinear sample at the same place, which
  // differs on this map (checked, so the comparison can tell them apart).
  int differ_from_bilinear = 0;
  for (const Texel& t : r.path) {
    const int ri = thx::tex::resolveIndex(t.i, s.map().width(), s.sampling().address);
    const int rj = thx::tex::resolveIndex(t.j, s.map().height(), s.sampling().address);
    const Eigen::Vector3d nearest = s.directionToWorld(s.map().normal(ri, rj).cast<double>().normalized());
    EXPECT_NEAR((t.n_world - nearest).norm(), 0.0, 1e-12);
    // The bilinear normal a quarter texel from the centre along the diagonal.
    const thx::tex::TexelPoint centre = s.texelPoint(t.i, t.j);
    const double q = 0.25 * s.texelSize();
    const Eigen::Vector3d bilinear = s.directionToWorld(s.at(centre.q_local.x() + q, centre.q_local.y() + q).n_local);
    differ_from_bilinear += (bilinear - nearest).norm() > 1e-4;
    // Path velocity: along the plane, at the ball's speed (it barely slows in 60 ms).
    EXPECT_NEAR(t.v_world.dot(s.mapping().geometricNormalWorld()), 0.0, 1e-9);
    EXPECT_NEAR(t.v_world.norm(), std::hypot(3.0, 1.4), 0.2);
  }
  EXPECT_GT(differ_from_bilinear, int(r.path.size()) / 2);
  std::printf("[measured] %zu texels in %d steps, at most %zu in one step\n", r.path.size(), r.steps_touching,
              r.most_in_one_step);
}

TEST(TexelPath, MessageCarriesEveryTexelAndDecodes) {
  const thx::scene::Scene scene = thx::scene::parseScene(kScene, "fast_ball.yaml", ".");
  SimOptions options;
  options.pen.shape = PenShape::None;
  PhysicsScene sim(scene, options);
  for (int k = 0; k < 20; ++k) sim.step(1e-3);  // 20 steps in one window: ~120 texels
  const std::vector<LastingContact> contacts = sim.takeContacts();
  ASSERT_EQ(contacts.size(), 1u);
  const thx_msgs::physics_contacts_t m = makeContacts(sim, contacts, 0.02, 1, 0);
  ASSERT_EQ(m.num_contacts, 1);
  EXPECT_DOUBLE_EQ(m.mass_a[0], 0.004);
  EXPECT_EQ(m.path_start[0], 0);
  ASSERT_EQ(std::size_t(m.num_texels[0]), contacts[0].path.size());
  ASSERT_TRUE(thx_msgs::path_count_consistent(m));
  EXPECT_EQ(m.n_geometric_world[2], 1.0);

  std::vector<std::uint8_t> bytes(std::size_t(m.getEncodedSize()));
  ASSERT_EQ(m.encode(bytes.data(), 0, int(bytes.size())), int(bytes.size()));
  EXPECT_EQ(bytes.size(), thx_msgs::physics_contacts_encoded_size(std::size_t(m.num_path)));
  EXPECT_EQ(thx_msgs::physics_contacts_encoded_size(0), 1140u);  // docs/messages.md §9
  EXPECT_EQ(thx_msgs::physics_texel_encoded_size(), 64u);
  thx_msgs::physics_contacts_t back;
  ASSERT_EQ(thx_msgs::try_decode(bytes.data(), bytes.size(), back), int(bytes.size()));
  ASSERT_EQ(back.num_path, m.num_path);
  for (int k = 0; k < m.num_path; ++k) {
    const Texel& t = contacts[0].path[std::size_t(k)];
    EXPECT_EQ(back.path[std::size_t(k)].i, t.i);
    EXPECT_EQ(back.path[std::size_t(k)].j, t.j);
    EXPECT_EQ(back.path[std::size_t(k)].t, t.t_s);
    EXPECT_EQ(back.path[std::size_t(k)].n_world[2], t.n_world.z());
  }
  // A count larger than the bytes can hold is refused before the decoder allocates.
  const std::size_t at = thx_msgs::physics_path_count_offset();
  bytes[at] = 0x01;  // num_path += 2^24
  EXPECT_EQ(thx_msgs::try_decode(bytes.data(), bytes.size(), back), -1);
  bytes[at] = 0x80;  // negative
  EXPECT_EQ(thx_msgs::try_decode(bytes.data(), bytes.size(), back), -1);
}

}  // namespace

}  // namespace test_texel_path
