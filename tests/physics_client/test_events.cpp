// Contact events and poses go out over LCM (memq://, in-process) as the new thx_msgs types and
// decode with try_decode; impacts name the pen and the ball, lasting contacts carry texel paths.
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>

#include "clients/physics_client/driver.hpp"
#include "clients/physics_client/lcm_io.hpp"
#include "clients/physics_client/pen_path.hpp"
#include "scenes/scene_loader.hpp"
#include "thx_msgs/protocol.hpp"

namespace test_events {

namespace {

using namespace thx::physclient;

struct Inbox {
  std::vector<thx_msgs::physics_poses_t> poses;
  std::vector<thx_msgs::physics_impact_t> impacts;
  std::vector<thx_msgs::physics_contacts_t> contacts;
  std::vector<thx_msgs::client_force_t> forces;
  int undecodable = 0;
  template <class T>
  void take(const lcm::ReceiveBuffer* rbuf, std::vector<T>& into) {
    T m;
    if (thx_msgs::try_decode(rbuf->data, rbuf->data_size, m) < 0) ++undecodable;
    else into.push_back(m);
  }
  void onPoses(const lcm::ReceiveBuffer* r, const std::string&) { take(r, poses); }
  void onImpact(const lcm::ReceiveBuffer* r, const std::string&) { take(r, impacts); }
  void onContacts(const lcm::ReceiveBuffer* r, const std::string&) { take(r, contacts); }
  void onForce(const lcm::ReceiveBuffer* r, const std::string&) { take(r, forces); }
};

TEST(PhysicsClientEvents, PublishedAndDecodable) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  Inbox in;
  lcm.subscribe(thx_msgs::kChannelPhysicsPoses, &Inbox::onPoses, &in);
  lcm.subscribe(thx_msgs::kChannelPhysicsImpact, &Inbox::onImpact, &in);
  lcm.subscribe(thx_msgs::kChannelPhysicsContacts, &Inbox::onContacts, &in);
  lcm.subscribe(thx_msgs::kChannelClientForce, &Inbox::onForce, &in);

  const thx::scene::Scene scene = thx::scene::loadScene(std::string(THX_SOURCE_DIR) + "/scenes/pen_pushes_ball.yaml");
  PhysicsScene sim(scene, SimOptions{});
  const PenPath path(penPathFromScript(sim, 1e-3));
  LcmSink sink(lcm, LcmSinkOptions{});
  DriverOptions d;
  d.contact_hz = 100;  // 10 steps per contact message: paths must carry every texel entered
  Driver driver(sim, sink, d);
  for (int k = 0; k < 2600; ++k) {
    driver.step(path.at(k * driver.dt()), 1000 + k);
    while (lcm.handleTimeout(0) > 0) {
    }
  }
  driver.flush();
  while (lcm.handleTimeout(0) > 0) {
  }
  EXPECT_EQ(in.undecodable, 0);

  // Poses at 60 Hz of 2.6 s, seq from 1, the ball = objects[0].
  EXPECT_NEAR(double(in.poses.size()), 2.6 * 60, 2);
  ASSERT_FALSE(in.poses.empty());
  EXPECT_EQ(in.poses.front().seq, 1);
  EXPECT_EQ(in.poses.back().num_bodies, 1);
  EXPECT_NEAR(in.poses.back().p_world[0][0], sim.body(0).p_world.x(), 0.01);
  EXPECT_GE(in.poses.back().ref_tick, 1000);

  // Impacts: the pen hits the ball at least once; every impact has a positive approach speed.
  bool pen_ball = false;
  for (const auto& i : in.impacts) {
    EXPECT_GT(i.v_approach, 0.0);
    EXPECT_GE(i.impulse, 0.0);
    pen_ball |= (i.body_a == 0 && i.body_b == thx_msgs::physics_impact_t::BODY_PEN);
  }
  EXPECT_TRUE(pen_ball) << in.impacts.size() << " impacts";

  // Lasting contacts: the ball on the surface, with its texel path; the path of consecutive
  // messages joins up (each texel entered is reported once, so neighbours differ by <= 1 texel
  // per step at these speeds, far less than the message's window).
  int with_path = 0, texels = 0;
  double max_f = 0;
  for (const auto& c : in.contacts) {
    ASSERT_LE(c.num_contacts, thx_msgs::physics_contacts_t::MAX_CONTACTS);
    for (int k = 0; k < c.num_contacts; ++k) {
      if (c.body_b[k] != thx_msgs::physics_contacts_t::BODY_SURFACE) continue;
      EXPECT_EQ(c.body_a[k], 0);
      with_path += c.num_texels[k] > 0;
      texels += c.num_texels[k];
      EXPECT_EQ(c.texels_dropped[k], 0);
      EXPECT_NEAR(c.mass_a[k], 0.0071, 1e-4);
      max_f = std::max(max_f, c.f_normal[k]);
    }
  }
  EXPECT_GT(with_path, 5);
  EXPECT_GT(texels, 50);  // the ball rolls tens of mm over 0.39 mm texels
  // The resting ball's weight, m g = 0.0071 * 9.81 = 0.07 N, shows in the normal force.
  EXPECT_GT(max_f, 0.05);

  // Client forces: sent while pushing, then a release (zero).
  ASSERT_FALSE(in.forces.empty());
  EXPECT_EQ(in.forces.front().source, "physics");
  bool released = false, pushed = false;
  for (const auto& f : in.forces) {
    const double n = std::sqrt(f.f_world[0] * f.f_world[0] + f.f_world[1] * f.f_world[1] + f.f_world[2] * f.f_world[2]);
    released |= n == 0.0;
    pushed |= n > 0.0;
    EXPECT_LE(n, 2.0 + 1e-9);
    EXPECT_EQ(f.tau_world[0], 0.0);
  }
  EXPECT_TRUE(pushed);
  EXPECT_TRUE(released);
}

TEST(PhysicsClientEvents, ContactsMessageBoundsPairsButNotPaths) {
  const thx::scene::Scene scene = thx::scene::loadScene(std::string(THX_SOURCE_DIR) + "/scenes/pen_pushes_ball.yaml");
  PhysicsScene sim(scene, SimOptions{});
  std::vector<LastingContact> many(12);
  for (std::size_t k = 0; k < many.size(); ++k) {
    many[k].body_b = kBodySurface;
    many[k].path.resize(40);
    for (std::size_t t = 0; t < 40; ++t) many[k].path[t].i = (long long)(100 * k + t);
    many[k].impulse_sum_ns = 0.01;
  }
  const thx_msgs::physics_contacts_t m = makeContacts(sim, many, 0.01, 1, 0);
  EXPECT_EQ(m.num_contacts, 8);
  EXPECT_EQ(m.num_dropped, 4);
  ASSERT_EQ(m.num_path, 8 * 40);
  for (int k = 0; k < 8; ++k) {
    EXPECT_EQ(m.num_texels[k], 40);
    EXPECT_EQ(m.path_start[k], 40 * k);
    EXPECT_EQ(m.texels_dropped[k], 0);
    EXPECT_EQ(m.path[std::size_t(m.path_start[k] + 39)].i, 100 * k + 39);
  }
  EXPECT_DOUBLE_EQ(m.f_normal[0], 1.0);
}

}  // namespace

}  // namespace test_events
