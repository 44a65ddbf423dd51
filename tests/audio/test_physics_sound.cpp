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

#include "clients/audio/offline/physics_sound.hpp"
#include "clients/audio/synthesis/contact_pulse.hpp"
#include "scenes/scene_loader.hpp"
#include "tests/audio/physics_fixtures.hpp"

namespace test_physics_sound {

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

// Ball 0 strikes ball 1 head-on: n from b (ball 1) to a (ball 0) is -x.
physics_impact_t ballOnBall(double impulse) {
  physics_impact_t m{};
  m.utime = 10'000;
  m.body_a = 0;
  m.body_b = 1;
  m.impulse = impulse;
  m.v_approach = 0.5;
  m.p_world[0] = 0.1;
  m.p_world[2] = 0.3;
  m.n_world[0] = -1.0;
  return m;
}

// |DFT| of x at f (Hz).
double magnitudeAt(const std::vector<double>& x, double f) {
  double re = 0, im = 0;
  for (std::size_t n = 0; n < x.size(); ++n) {
    const double w = 2.0 * std::numbers::pi * f * double(n) / kFs;
    re += x[n] * std::cos(w);
    im -= x[n] * std::sin(w);
  }
  return std::hypot(re, im);
}

// The frequency of the body's mode struck hardest at `point` along `direction`, among those at
// least 1 % away from every mode of `other` (so the other ball cannot ring there too: the two
// balls' spectra interleave, and which modes lie close depends on the mesh).
double loudestModeApartFrom(const ModalBody& body, const Eigen::Vector3d& point, const Eigen::Vector3d& direction,
                            const ModalBody& other) {
  const std::vector<double> g = body.gainsAt(point, direction);
  const std::vector<double>& f = body.modes().frequency_hz;
  const auto apart = [&](double fi) {
    for (double fo : other.modes().frequency_hz)
      if (std::fabs(fi - fo) < 0.01 * fi) return false;
    return true;
  };
  std::size_t best = g.size();
  for (std::size_t i = 0; i < g.size(); ++i)
    if (apart(f[i]) && (best == g.size() || std::fabs(g[i]) > std::fabs(g[best]))) best = i;
  EXPECT_LT(best, g.size()) << "no mode 1 % away from the other body's";
  return best < g.size() ? f[best] : 0.0;
}

TEST(PhysicsSound, TwoObjectsStrikingEachOtherRingBothOfTheirModes) {
  const SoundingScene& sc = twoBalls();
  ASSERT_TRUE(sc.objects.at(0) && sc.objects.at(1));
  ASSERT_GT(sc.objects[0]->size(), 0u);
  ASSERT_GT(sc.objects[1]->size(), 0u);
  const double f0 = loudestModeApartFrom(*sc.objects[0], {0.1, 0, 0}, {-1, 0, 0}, *sc.objects[1]);
  const double f1 = loudestModeApartFrom(*sc.objects[1], {-0.13, 0, 0}, {1, 0, 0}, *sc.objects[0]);
  std::printf("[measured] ball 0: %zu modes %.0f-%.0f Hz, struck hardest at %.1f Hz; ball 1: %zu modes %.0f-%.0f Hz, at %.1f Hz\n",
              sc.objects[0]->size(), sc.objects[0]->modes().frequency_hz.front(), sc.objects[0]->modes().frequency_hz.back(), f0,
              sc.objects[1]->size(), sc.objects[1]->modes().frequency_hz.front(), sc.objects[1]->modes().frequency_hz.back(), f1);

  PhysicsStreams s;
  s.poses.push_back(twoBallPoses());
  s.impacts.push_back(ballOnBall(1e-3));
  const PhysicsRender r = render(s, sc);
  EXPECT_EQ(r.impacts, 1u);
  EXPECT_EQ(r.strikes, 2u) << "both balls, not the surface";
  EXPECT_EQ(r.object_impacts, 1u);
  // The Hertz time from both sides: steel on steel, 1/R* = 1/0.1 + 1/0.13, 1/m* = 1/m0 + 1/m1.
  const auto side = [&](std::size_t k) {
    const thx::scene::SceneObject& o = sc.scene.objects[k];
    return HertzSide{o.material.youngs_modulus_pa, o.material.poisson_ratio, o.radius_m, o.mass_kg};
  };
  EXPECT_GT(r.min_contact_s, 0.0);
  EXPECT_DOUBLE_EQ(r.min_contact_s, hertzContactDuration(side(0), side(1), 0.5));

  // Each ball's mode is in the sound, and goes when that ball has no modes.
  SoundingScene without0 = sc, without1 = sc;
  without0.objects[0] = nullptr;
  without1.objects[1] = nullptr;
  const PhysicsRender r0 = render(s, without1), r1 = render(s, without0);  // ball 0 alone, ball 1 alone
  EXPECT_EQ(r0.strikes, 1u);
  EXPECT_EQ(r1.strikes, 1u);
  // The render is linear in the bodies: the sound of both is ball 0's plus ball 1's, and each
  // ball's share is audible (its RMS a sizeable part of the whole).
  ASSERT_EQ(r0.samples.size(), r.samples.size());
  ASSERT_EQ(r1.samples.size(), r.samples.size());
  double e = 0, e0 = 0, e1 = 0, diff = 0;
  for (std::size_t n = 0; n < r.samples.size(); ++n) {
    e += r.samples[n] * r.samples[n];
    e0 += r0.samples[n] * r0.samples[n];
    e1 += r1.samples[n] * r1.samples[n];
    const double d = r.samples[n] - r0.samples[n] - r1.samples[n];
    diff += d * d;
  }
  std::printf("[measured] RMS ratio ball 0 / both %.3f, ball 1 / both %.3f; superposition residual %.3g of both\n",
              std::sqrt(e0 / e), std::sqrt(e1 / e), std::sqrt(diff / e));
  EXPECT_LT(std::sqrt(diff / e), 1e-9);
  EXPECT_GT(std::sqrt(e0 / e), 0.05);
  EXPECT_GT(std::sqrt(e1 / e), 0.05);
  // Each ball's own mode (one no mode of the other ball lies within 1 % of) is in the sound of
  // both: the mix there is the ringing ball's, not less.
  EXPECT_GT(magnitudeAt(r.samples, f0), 0.5 * magnitudeAt(r0.samples, f0));
  EXPECT_GT(magnitudeAt(r.samples, f1), 0.5 * magnitudeAt(r1.samples, f1));
  // The same every time.
  EXPECT_EQ(render(s, sc).samples, r.samples);

  // No impulse, no sound.
  PhysicsStreams zero = s;
  zero.impacts[0].impulse = 0.0;
  const PhysicsRender silent = render(zero, sc);
  EXPECT_EQ(silent.impacts, 0u);
  EXPECT_EQ(silent.strikes, 0u);
  EXPECT_TRUE(silent.samples.empty());
}

TEST(PhysicsSound, AnImpactWithThePenRingsThePenAtItsTip) {
  // A test double for the pen's modes: the 13 cm ball's body, struck at its node 0.
  SoundingScene sc = twoBalls();
  PhysicsStreams s;
  s.poses.push_back(twoBallPoses());
  physics_impact_t m = ballOnBall(1e-3);
  m.body_b = physics_impact_t::BODY_PEN;
  s.impacts.push_back(m);
  const PhysicsRender no_pen = render(s, sc);
  EXPECT_EQ(no_pen.strikes, 1u) << "the ball alone: no pen modes";
  sc.pen = sc.objects[1];
  sc.pen_tip_node = 0;
  const PhysicsRender with_pen = render(s, sc);
  EXPECT_EQ(with_pen.strikes, 2u);
  double diff = 0;
  for (std::size_t n = 0; n < std::min(no_pen.samples.size(), with_pen.samples.size()); ++n)
    diff = std::max(diff, std::fabs(with_pen.samples[n] - no_pen.samples[n]));
  EXPECT_GT(diff, 0.0);
}

}  // namespace

}  // namespace test_physics_sound
