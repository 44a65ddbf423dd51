// The physics client's streams live (clients/audio/live/physics_source.hpp): every strike of the
// shared PhysicsExcitation as a Point event on its SynthScene body, at its time plus the playout
// delay; impacts on both bodies with their Hertz contact time; the texel walk carried across
// messages and restarted when the body loses contact; the pen's entries, object pairs and
// objects without a pose give no object strike; impacts between two objects ring both, impacts
// with the pen ring the pen's body.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "clients/audio/live/physics_source.hpp"
#include "clients/audio/synthesis/contact_pulse.hpp"
#include "tests/audio/physics_fixtures.hpp"

namespace thx::audio::test_physics_source {
namespace {

using test::testScene;

struct VectorSink final : ExcitationSink {
  std::vector<ExcitationEvent> events;
  void push(const ExcitationEvent& e) override { events.push_back(e); }
};

const Eigen::Vector3d kFlat(0, 0, 1);
const Eigen::Vector3d kTilted(std::sin(0.3), 0, std::cos(0.3));

TEST(PhysicsSource, AnImpactStrikesBothBodiesAtTheCentreOfItsHertzPulse) {
  const SoundingScene& sc = testScene();
  PhysicsSource source(sc, {1}, 3, 2'000'000);
  VectorSink sink;
  source.physicsPoses(test::ballPose(0), 0);
  const thx_msgs::physics_impact_t m = test::impact(100'000, 0.5);
  source.physicsImpact(m, 77, sink);
  ASSERT_EQ(sink.events.size(), 2u);
  const HertzSide steel{sc.scene.objects[0].material.youngs_modulus_pa, sc.scene.objects[0].material.poisson_ratio, 0.1,
                        sc.scene.objects[0].mass_kg};
  const HertzSide surface{sc.scene.surface.material.youngs_modulus_pa, sc.scene.surface.material.poisson_ratio};
  const double tau = hertzContactDuration(steel, surface, 0.5);
  EXPECT_NEAR(source.counts().min_contact_s, tau, 1e-15);
  for (const ExcitationEvent& e : sink.events) {
    EXPECT_EQ(e.kind, ExcitationKind::Point);
    EXPECT_EQ(e.generation, 3u);
    EXPECT_EQ(e.receipt_ns, 77);
    EXPECT_EQ(e.source_ns, 100'000'000);
    EXPECT_DOUBLE_EQ(e.pulse_s, tau);
    EXPECT_EQ(e.time_ns, 100'000'000 + std::llround(0.5 * tau * 1e9) + 2'000'000);
    EXPECT_EQ(e.point_count, e.body == 1 ? 4 : 10);  // the ball is Tet4 here, the slab Tet10
  }
  // The ball (body 1) gets +J along n, the surface (body 0) -J, each in its own frame.
  const ExcitationEvent& ball = sink.events[0].body == 1 ? sink.events[0] : sink.events[1];
  const ExcitationEvent& slab = sink.events[0].body == 1 ? sink.events[1] : sink.events[0];
  EXPECT_EQ(ball.body, 1);
  EXPECT_EQ(slab.body, 0);
  EXPECT_NEAR(ball.impulse[2], 1e-3, 1e-15);
  EXPECT_NEAR(slab.impulse[2], -1e-3, 1e-15);
  // The weights are the ModalBody's: they reproduce its gains at the point.
  double sum = 0;
  for (int c = 0; c < ball.point_count; ++c) sum += ball.point_weights[c];
  EXPECT_NEAR(sum, 1.0, 1e-12);
}

TEST(PhysicsSource, TwoObjectsAndThePenEachRingTheirOwnBody) {
  // The test ball twice (objects 0 and 1 on SynthScene bodies 1 and 2), the pen's double on body 3:
  // the ball's modal body struck at its node 0.
  SoundingScene sc = testScene();
  sc.objects.push_back(sc.objects[0]);
  sc.pen = sc.objects[0];
  sc.pen_tip_node = 0;
  PhysicsSource source(sc, {1, 2}, 1, 0, 3);
  VectorSink sink;
  thx_msgs::physics_poses_t poses = test::ballPose(0);
  poses.num_bodies = 2;
  poses.p_world[1][0] = 0.2;  // ball 1 beside ball 0, touching at x = 0.1
  poses.p_world[1][2] = 0.1;
  poses.q_world[1][0] = 1.0;
  source.physicsPoses(poses, 0);
  thx_msgs::physics_impact_t m = test::impact(1000, 0.5);
  m.body_b = 1;
  m.p_world[0] = 0.1;
  m.p_world[1] = 0.0;
  m.p_world[2] = 0.1;
  m.n_world[0] = -1.0;
  m.n_world[2] = 0.0;
  source.physicsImpact(m, 0, sink);
  ASSERT_EQ(sink.events.size(), 2u);
  EXPECT_EQ(sink.events[0].body + sink.events[1].body, 1 + 2);  // both balls, not the surface
  EXPECT_NEAR(sink.events[0].impulse[0] + sink.events[1].impulse[0], 0.0, 1e-15);  // +J on a, -J on b
  EXPECT_EQ(source.counts().object_impacts, 1u);

  sink.events.clear();
  m.body_b = thx_msgs::physics_impact_t::BODY_PEN;
  source.physicsImpact(m, 0, sink);
  ASSERT_EQ(sink.events.size(), 2u);
  EXPECT_EQ(sink.events[0].body + sink.events[1].body, 1 + 3);  // ball 0 and the pen
}

TEST(PhysicsSource, TexelPathsStrikeTheSurfaceAndTheObjectAtTheirEntryTimes) {
  const SoundingScene& sc = testScene();
  PhysicsSource source(sc, {1}, 1, 0);
  VectorSink sink;
  source.physicsPoses(test::ballPose(0), 0);
  source.physicsContacts(test::pathMessage(1000, 1e-3, {kFlat, kTilted}, 0), 0, sink);
  source.physicsContacts(test::pathMessage(2000, 2e-3, {kTilted, kFlat}, 2), 0, sink);
  EXPECT_EQ(source.counts().meso_impulses, 2u);  // into the tilted texels, out of them
  ASSERT_EQ(sink.events.size(), 4u);             // each on the surface and the ball
  // Eq. 5 by hand: -(v . n_s) / (n_g . n_s) n_g m = -0.3 tan 0.3 x 0.1 entering, the opposite leaving.
  const double j = -0.1 * 0.3 * std::tan(0.3);
  EXPECT_EQ(sink.events[0].body, 0);
  EXPECT_NEAR(sink.events[0].impulse[2], -j, 1e-6 * std::fabs(j));  // the surface: -dp
  EXPECT_EQ(sink.events[1].body, 1);
  EXPECT_NEAR(sink.events[1].impulse[2], j, 1e-6 * std::fabs(j));   // the ball: +dp
  EXPECT_NEAR(sink.events[2].impulse[2], j, 1e-6 * std::fabs(j));
  EXPECT_NEAR(sink.events[3].impulse[2], -j, 1e-6 * std::fabs(j));
  // At the entry times: 1 ms (the second texel of the first message), 2 ms (the second of the next).
  EXPECT_EQ(sink.events[0].time_ns, 1'000'000);
  EXPECT_EQ(sink.events[2].time_ns, 2'000'000);
}

TEST(PhysicsSource, TheWalkRestartsAfterLosingContactAndSkipsThePenAndObjectPairs) {
  const SoundingScene& sc = testScene();
  PhysicsSource source(sc, {1}, 1, 0);
  VectorSink sink;
  source.physicsPoses(test::ballPose(0), 0);
  source.physicsContacts(test::pathMessage(1000, 1e-3, {kFlat}, 0), 0, sink);
  // The ball is missing from the next report: the walk ends; the tilted texel after it is a
  // new walk's first (no impulse).
  thx_msgs::physics_contacts_t none = test::pathMessage(2000, 2e-3, {}, 0);
  none.num_contacts = 0;
  source.physicsContacts(none, 0, sink);
  source.physicsContacts(test::pathMessage(3000, 3e-3, {kTilted}, 1), 0, sink);
  EXPECT_TRUE(sink.events.empty());
  // The pen's entries and object pairs give none.
  thx_msgs::physics_contacts_t pen = test::pathMessage(4000, 4e-3, {kFlat, kTilted}, 5);
  pen.body_a[0] = thx_msgs::physics_contacts_t::BODY_PEN;
  source.physicsContacts(pen, 0, sink);
  thx_msgs::physics_contacts_t pair = test::pathMessage(5000, 5e-3, {kFlat, kTilted}, 7);
  pair.body_b[0] = 1;
  source.physicsContacts(pair, 0, sink);
  EXPECT_TRUE(sink.events.empty());
}

TEST(PhysicsSource, WithoutAPoseOrAudibleModesOnlyTheSurfaceSounds) {
  const SoundingScene& sc = testScene();
  VectorSink sink;
  PhysicsSource no_pose(sc, {1}, 1, 0);  // no THX_PHYSICS_POSES yet: the ball's frame is unknown
  no_pose.physicsImpact(test::impact(100'000, 0.5), 0, sink);
  ASSERT_EQ(sink.events.size(), 1u);
  EXPECT_EQ(sink.events[0].body, 0);
  sink.events.clear();
  PhysicsSource silent_ball(sc, {-1}, 1, 0);  // the ball has no SynthScene body
  silent_ball.physicsPoses(test::ballPose(0), 0);
  silent_ball.physicsImpact(test::impact(100'000, 0.5), 0, sink);
  ASSERT_EQ(sink.events.size(), 1u);
  EXPECT_EQ(sink.events[0].body, 0);
}

}  // namespace
}  // namespace thx::audio::test_physics_source
