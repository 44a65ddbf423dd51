// The physics client's streams made audible (physics_sound.hpp, docs/audio.md §9–§10): impacts on
// both bodies after a Hertz contact time, Eq. 5 texel paths on a normal map, the relief's momentum
// changes, scene switches, and the same samples every time.
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include <thx_msgs/hello_t.hpp>
#include <thx_msgs/log_reader.hpp>

#include "clients/audio/physics_sound.hpp"
#include "tests/audio/physics_fixtures.hpp"
#include "scenes/scene_loader.hpp"

namespace {

using namespace thx::audio;
using namespace thx::audio::test;
using thx_msgs::physics_contacts_t;
using thx_msgs::physics_impact_t;

constexpr double kFs = 44100.0;

PhysicsRender render(const PhysicsStreams& s, const SoundingScene& first = testScene()) {
  PhysicsSoundOptions o;
  o.sample_rate_hz = kFs;
  o.tail_s = 0.2;
  return renderPhysicsStreams(s, first, [&](const std::string& name) {
    SoundingScene other = first;
    other.name = name;
    return other;
  }, 0, o);
}

std::size_t firstSound(const std::vector<double>& x) {
  for (std::size_t n = 0; n < x.size(); ++n)
    if (x[n] != 0.0) return n;
  return x.size();
}

TEST(PhysicsSound, ImpactRingsBothBodiesAfterTheHertzTime) {
  const SoundingScene& sc = testScene();
  ASSERT_GT(sc.surface->size(), 3u);
  ASSERT_TRUE(sc.objects.at(0));
  ASSERT_GT(sc.objects[0]->size(), 0u) << "the 10 cm steel ball should have audible modes";
  std::printf("[measured] slab %zu modes (%.0f-%.0f Hz), ball %zu modes (%.0f-%.0f Hz)\n", sc.surface->size(),
              sc.surface->modes().frequency_hz.front(), sc.surface->modes().frequency_hz.back(), sc.objects[0]->size(),
              sc.objects[0]->modes().frequency_hz.front(), sc.objects[0]->modes().frequency_hz.back());
  PhysicsStreams s;
  s.poses.push_back(ballPose(0));
  s.impacts.push_back(impact(100'000, 0.5));
  const PhysicsRender r = render(s);
  EXPECT_EQ(r.impacts, 1u);
  EXPECT_EQ(r.strikes, 2u);  // the ball and the surface
  EXPECT_GT(r.min_contact_s, 0.0);
  // Silent until the pulse's centre: 0.1 s + tau / 2.
  EXPECT_EQ(firstSound(r.samples), std::size_t(std::llround((0.1 + 0.5 * r.min_contact_s) * kFs)) + 1);

  // Both bodies sound: without the ball's modes the track differs.
  SoundingScene surface_only = sc;
  surface_only.objects[0] = nullptr;
  const PhysicsRender r_surface = render(s, surface_only);
  EXPECT_EQ(r_surface.strikes, 1u);
  double diff = 0;
  for (std::size_t n = 0; n < r.samples.size(); ++n) diff = std::max(diff, std::fabs(r.samples[n] - r_surface.samples[n]));
  EXPECT_GT(diff, 0.0);

  // A faster impact is shorter (v^-1/5) and the same every time.
  PhysicsStreams fast = s;
  fast.impacts[0].v_approach = 0.5 * 32;
  const PhysicsRender rf = render(fast);
  EXPECT_NEAR(r.min_contact_s / rf.min_contact_s, 2.0, 1e-9);
  EXPECT_EQ(render(s).samples, r.samples);
}

TEST(PhysicsSound, TexelPathsGiveEq5ImpulsesOnANormalMap) {
  const Eigen::Vector3d flat(0, 0, 1), tilted = Eigen::Vector3d(std::sin(0.3), 0, std::cos(0.3));
  PhysicsStreams s;
  s.poses.push_back(ballPose(0));
  s.contacts.push_back(pathMessage(1000, 1e-3, {flat, tilted}, 0));
  s.contacts.push_back(pathMessage(2000, 2e-3, {tilted, flat}, 2));
  const PhysicsRender r = render(s);
  EXPECT_EQ(r.meso_impulses, 2u);  // into the tilted texels, out of them
  EXPECT_EQ(r.strikes, 4u);        // each on the surface and the ball
  EXPECT_EQ(r.relief_impulses, 0u);
  // The first is struck where the path entered the tilted texel: t = 1 ms.
  EXPECT_EQ(firstSound(r.samples), std::size_t(std::llround(1e-3 * kFs)) + 1);

  PhysicsStreams flat_path;
  flat_path.poses = s.poses;
  flat_path.contacts.push_back(pathMessage(1000, 1e-3, {flat, flat, flat}, 0));
  const PhysicsRender silent = render(flat_path);
  EXPECT_EQ(silent.meso_impulses, 0u);
  EXPECT_TRUE(silent.samples.empty());
}

TEST(PhysicsSound, ReliefContactsGiveTheChangeOfNormalMomentum) {
  SoundingScene relief = testScene();
  relief.relief = true;
  PhysicsStreams s;
  s.poses.push_back(ballPose(0));
  for (int k = 0; k < 4; ++k) {
    physics_contacts_t m = pathMessage(1000 * (k + 1), 1e-3 * (k + 1), {}, 0);
    m.v_world[0][0] = 0.3;
    m.v_world[0][2] = k == 2 ? -0.05 : 0.0;  // dips once: two changes
    s.contacts.push_back(m);
  }
  const PhysicsRender r = render(s, relief);
  EXPECT_EQ(r.relief_impulses, 2u);
  EXPECT_EQ(r.meso_impulses, 0u);
  EXPECT_EQ(firstSound(r.samples), std::size_t(std::llround(3e-3 * kFs)) + 1);
}

TEST(PhysicsSound, FollowsSceneSwitchesAnnouncedInTheLog) {
  PhysicsStreams s;
  s.poses.push_back(ballPose(0));
  s.impacts.push_back(impact(100'000, 0.5));
  s.hellos.push_back({50'000, "marble_rolling_bricks"});  // the same scene: no switch
  s.hellos.push_back({200'000, "other"});
  s.poses.push_back(ballPose(210'000));
  s.impacts.push_back(impact(300'000, 0.5));
  const PhysicsRender r = render(s);
  EXPECT_EQ(r.impacts, 2u);
  ASSERT_EQ(r.scenes.size(), 2u);
  EXPECT_EQ(r.scenes[0], "marble_rolling_bricks");
  EXPECT_EQ(r.scenes[1], "other");
}

// The streams as a log holds them: the physics events in order, hellos with their scene, poses
// ordered by time; an event that does not decode is an error naming the file and the event.
TEST(PhysicsSound, ReadsThePhysicsStreamsOfALog) {
  const std::string file = "/tmp/thx_physics_sound_" + std::to_string(::getpid()) + ".lcm";
  {
    lcm::LogFile log(file, "w");
    ASSERT_TRUE(log.good());
    std::vector<std::uint8_t> buf;
    auto put = [&](const char* channel, const auto& m) {
      buf.resize(std::size_t(m.getEncodedSize()));
      m.encode(buf.data(), 0, int(buf.size()));
      lcm::LogEvent e{};
      e.channel = channel;
      e.datalen = std::int32_t(buf.size());
      e.data = buf.data();
      ASSERT_EQ(log.writeEvent(&e), 0);
    };
    thx_msgs::hello_t h{};
    h.utime = 10;
    h.scene_name = "other";
    put(thx_msgs::kChannelHello, h);
    put(thx_msgs::kChannelPhysicsPoses, ballPose(2000));
    put(thx_msgs::kChannelPhysicsPoses, ballPose(1000));
    put(thx_msgs::kChannelPhysicsImpact, impact(1500, 0.5));
    put(thx_msgs::kChannelPhysicsContacts, pathMessage(1000, 1e-3, {Eigen::Vector3d(0, 0, 1)}, 0));
    put("THX_SOMETHING_ELSE", h);
  }
  const PhysicsStreams s = readPhysicsStreams(file);
  ASSERT_EQ(s.hellos.size(), 1u);
  EXPECT_EQ(s.hellos[0].scene_name, "other");
  EXPECT_EQ(s.hellos[0].utime, 10);
  ASSERT_EQ(s.poses.size(), 2u);
  EXPECT_EQ(s.poses[0].utime, 1000);
  EXPECT_EQ(s.impacts.size(), 1u);
  ASSERT_EQ(s.contacts.size(), 1u);
  EXPECT_EQ(s.contacts[0].num_path, 1);
  EXPECT_EQ(s.firstUtime(), 1000);
  {  // an impact channel carrying a hello
    lcm::LogFile log(file, "w");
    thx_msgs::hello_t h{};
    std::vector<std::uint8_t> buf(std::size_t(h.getEncodedSize()));
    h.encode(buf.data(), 0, int(buf.size()));
    lcm::LogEvent e{};
    e.channel = thx_msgs::kChannelPhysicsImpact;
    e.datalen = std::int32_t(buf.size());
    e.data = buf.data();
    ASSERT_EQ(log.writeEvent(&e), 0);
  }
  try {
    readPhysicsStreams(file);
    ADD_FAILURE() << "expected an error";
  } catch (const thx_msgs::LogError& e) {
    EXPECT_NE(std::string(e.what()).find(file + ": event 1 (THX_PHYSICS_IMPACT): does not decode as"), std::string::npos)
        << e.what();
  }
  std::remove(file.c_str());
}

}  // namespace
