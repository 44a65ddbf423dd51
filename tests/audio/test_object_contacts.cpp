// Lasting contacts between two objects (issue 14: every contact excites both sides; docs/audio.md
// §10a): two audible steel balls touching, one sliding or rolling on the other. Each contacts
// report becomes a micro-level force segment (the roughness read along the contact's travel,
// scaled by the normal force) on both balls, opposite, each at the contact point in its own frame;
// offline (physics_sound.hpp) and live (physics_source.hpp + synth_scene.hpp) the same.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "clients/audio/live/live_scene.hpp"
#include "clients/audio/live/physics_source.hpp"
#include "clients/audio/synthesis/object_contact.hpp"
#include "clients/audio/synthesis/surface_sound.hpp"
#include "clients/audio/synthesis/synth_scene.hpp"
#include "tests/audio/physics_fixtures.hpp"

namespace thx::audio::test_object_contacts {
namespace {

using test::rubMessage;
using test::twoBalls;
using test::twoBallPoses;

constexpr double kFs = 44100.0;
constexpr int kReports = 40;  // 40 ms of contact at the physics client's 1 kHz reports

const Eigen::Vector3d kZero(0, 0, 0);

// Ball 0 on ball 1 for kReports milliseconds: slipping at `slip`, its centre at `v_a`, pushed with `force`.
PhysicsStreams rubbing(const Eigen::Vector3d& slip, const Eigen::Vector3d& v_a, double force) {
  PhysicsStreams s;
  s.poses.push_back(twoBallPoses());
  for (int k = 1; k <= kReports; ++k) s.contacts.push_back(rubMessage(1000 * k, slip, v_a, force));
  return s;
}

PhysicsRender render(const PhysicsStreams& s, const SoundingScene& sc = twoBalls(), bool object_contacts = true) {
  PhysicsSoundOptions o;
  o.sample_rate_hz = kFs;
  o.tail_s = 0.05;
  o.object_contacts.enabled = object_contacts;
  return renderPhysicsStreams(s, sc, [&](const std::string&) { return sc; }, 0, o);
}

double energy(const std::vector<double>& x) {
  double e = 0;
  for (double v : x) e += v * v;
  return e;
}

TEST(ObjectContact, SlidingReadsAtTheSlipSpeedRollingAtTheTravelSpeedAndQuieter) {
  const ObjectContactOptions o;
  const ContactTravel slide = contactTravel(0.3, 0.3, o);  // sliding without turning
  EXPECT_EQ(slide.speed_m_per_s, 0.3);
  EXPECT_EQ(slide.weight, 1.0);
  const ContactTravel roll = contactTravel(0.0, 0.3, o);   // rolling without slip
  EXPECT_EQ(roll.speed_m_per_s, 0.3);
  EXPECT_EQ(roll.weight, o.rolling_share);
  const ContactTravel spin = contactTravel(0.3, 0.0, o);   // spinning in place: sliding
  EXPECT_EQ(spin.weight, 1.0);
  const ContactTravel skid = contactTravel(0.1, 0.4, o);   // rolling with some slip
  EXPECT_DOUBLE_EQ(skid.weight, (0.1 + o.rolling_share * 0.3) / 0.4);
  EXPECT_EQ(contactTravel(0.0, 0.0, o).weight, 0.0);        // at rest
  EXPECT_EQ(contactTravel(0.5 * o.min_speed_m_per_s, 0.0, o).speed_m_per_s, 0.0);  // resting jitter
}

TEST(ObjectContacts, EachReportIsAForceSegmentOnBothBallsOppositeAtTheContact) {
  const SoundingScene& sc = twoBalls();
  PhysicsExcitation x(sc);
  const thx_msgs::physics_poses_t poses = twoBallPoses();
  const PoseLookup lookup = [&](std::int64_t) { return &poses; };
  std::vector<BodyStrike> got;
  const StrikeSink sink = [&](const BodyStrike& s) {
    got.push_back(s);
    return true;
  };
  const Eigen::Vector3d slip(0, 0.2, 0);  // ball 0 slides along +y on ball 1, not turning
  x.contacts(rubMessage(1000, slip, slip, 10.0), lookup, sink);
  x.contacts(rubMessage(2000, slip, slip, 12.0), lookup, sink);
  ASSERT_EQ(got.size(), 4u);
  EXPECT_EQ(x.counts().object_contact_segments, 2u);
  for (std::size_t k = 0; k < got.size(); ++k) {
    const BodyStrike& s = got[k];
    const bool a = k % 2 == 0;
    EXPECT_TRUE(s.micro);
    EXPECT_EQ(s.body, a ? 0 : 1);
    // The segment covers the report's window; the roughness is read 0.2 m/s x 1 ms further each time.
    EXPECT_EQ(s.utime, std::int64_t(1000 * (k / 2)));
    EXPECT_EQ(s.end_utime, std::int64_t(1000 * (k / 2 + 1)));
    EXPECT_NEAR(s.s1 - s.s0, 0.2e-3, 1e-15);
    // The contact point in each ball's frame, +n on ball 0 and -n on ball 1 (n = -x).
    EXPECT_NEAR((s.point - Eigen::Vector3d(a ? 0.1 : 0.1 - test::kGap, 0, 0)).norm(), 0.0, 1e-12);
    EXPECT_NEAR((s.impulse - Eigen::Vector3d(a ? -1 : 1, 0, 0)).norm(), 0.0, 1e-12);
  }
  EXPECT_EQ(got[2].s0, got[0].s1);  // the read goes on from report to report
  EXPECT_EQ(got[0].f0, 0.0);        // a contact that starts moving fades in over one window
  EXPECT_EQ(got[0].f1, 10.0);
  EXPECT_EQ(got[2].f0, 10.0);
  EXPECT_EQ(got[2].f1, 12.0);
}

TEST(ObjectContacts, SlidingBallsSoundOnBothBallsEachShareAudible) {
  const SoundingScene& sc = twoBalls();
  const Eigen::Vector3d slip(0, 0.5, 0);
  const PhysicsStreams s = rubbing(slip, slip, 10.0);
  const PhysicsRender r = render(s);
  EXPECT_EQ(r.object_contact_segments, std::size_t(kReports));
  EXPECT_EQ(r.strikes, std::size_t(2 * kReports)) << "both balls, not the surface";
  EXPECT_EQ(r.impacts + r.meso_impulses + r.relief_impulses, 0u);
  ASSERT_FALSE(r.samples.empty());

  // Each ball alone (the other's modes removed): the sound of both is their sum, each share audible.
  SoundingScene without0 = sc, without1 = sc;
  without0.objects[0] = nullptr;
  without1.objects[1] = nullptr;
  const PhysicsRender r0 = render(s, without1), r1 = render(s, without0);
  EXPECT_EQ(r0.strikes, std::size_t(kReports));
  EXPECT_EQ(r1.strikes, std::size_t(kReports));
  ASSERT_EQ(r0.samples.size(), r.samples.size());
  ASSERT_EQ(r1.samples.size(), r.samples.size());
  std::vector<double> residual(r.samples.size());
  for (std::size_t n = 0; n < r.samples.size(); ++n) residual[n] = r.samples[n] - r0.samples[n] - r1.samples[n];
  const double e = energy(r.samples), e0 = energy(r0.samples), e1 = energy(r1.samples);
  std::printf("[measured] sliding 0.5 m/s, 10 N: RMS ball 0 / both %.3f, ball 1 / both %.3f; residual %.3g of both\n",
              std::sqrt(e0 / e), std::sqrt(e1 / e), std::sqrt(energy(residual) / e));
  EXPECT_LT(std::sqrt(energy(residual) / e), 1e-9);
  EXPECT_GT(std::sqrt(e0 / e), 0.05);
  EXPECT_GT(std::sqrt(e1 / e), 0.05);
  EXPECT_EQ(render(s).samples, r.samples);  // the same every time
  EXPECT_TRUE(render(s, sc, false).samples.empty()) << "--no-object-contacts";
}

TEST(ObjectContacts, LouderWithTheNormalForceBrighterWithTheSpeedQuieterRolling) {
  const Eigen::Vector3d y(0, 1, 0);
  const PhysicsRender base = render(rubbing(0.5 * y, 0.5 * y, 10.0));
  const PhysicsRender twice = render(rubbing(0.5 * y, 0.5 * y, 20.0));
  ASSERT_EQ(twice.samples.size(), base.samples.size());
  // The force scales the roughness: twice the push, twice the sound (the read is the same).
  double worst = 0;
  for (std::size_t n = 0; n < base.samples.size(); ++n) worst = std::max(worst, std::fabs(twice.samples[n] - 2.0 * base.samples[n]));
  const double peak = *std::max_element(base.samples.begin(), base.samples.end(),
                                        [](double a, double b) { return std::fabs(a) < std::fabs(b); });
  EXPECT_LT(worst, 1e-12 * std::fabs(peak));
  EXPECT_NEAR(energy(twice.samples) / energy(base.samples), 4.0, 1e-9);

  // Rolling without slip at the same travel speed: the same read, rolling_share of the force.
  const PhysicsRender rolling = render(rubbing(kZero, 0.5 * y, 10.0));
  EXPECT_EQ(rolling.object_contact_segments, std::size_t(kReports));
  EXPECT_NEAR(std::sqrt(energy(rolling.samples) / energy(base.samples)), ObjectContactOptions{}.rolling_share, 1e-9);

  // The relative speed sets how fast the roughness is read: at 0.1 m/s its finest wavelength
  // (20 µm) passes at 5 kHz, below the balls' modes (10-16 kHz); at 0.5 m/s at 25 kHz. So the
  // faster rub excites them much more (the profile is 1/f: equal power per octave of the read).
  const PhysicsRender slow = render(rubbing(0.1 * y, 0.1 * y, 10.0));
  const double ratio = energy(base.samples) / energy(slow.samples);
  std::printf("[measured] energy at 0.5 m/s / at 0.1 m/s: %.3g\n", ratio);
  EXPECT_GT(ratio, 10.0);
}

TEST(ObjectContacts, AtRestTheContactIsExactlySilent) {
  const Eigen::Vector3d y(0, 1, 0);
  // Pushing hard but not moving, or moving below the resting threshold: no segment, no sample.
  for (const double v : {0.0, 0.5 * ObjectContactOptions{}.min_speed_m_per_s}) {
    const PhysicsRender r = render(rubbing(v * y, v * y, 50.0));
    EXPECT_EQ(r.object_contact_segments, 0u) << v;
    EXPECT_EQ(r.strikes, 0u) << v;
    EXPECT_TRUE(r.samples.empty()) << v;
  }
  // Moving without a push: silent too; and reports no physics client sends (a window above 1 s,
  // a speed or a force that is not finite) make nothing.
  EXPECT_TRUE(render(rubbing(0.5 * y, 0.5 * y, 0.0)).samples.empty());
  PhysicsStreams odd = rubbing(0.5 * y, 0.5 * y, 10.0);
  odd.contacts.resize(3);
  odd.contacts[0].window = 2.0;
  odd.contacts[1].v_slip_world[0][1] = std::numeric_limits<double>::infinity();
  odd.contacts[2].f_normal[0] = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(render(odd).samples.empty());
  // An impact with the contact at rest afterwards sounds as the impact alone, to the bit.
  PhysicsStreams with_rest = rubbing(kZero, kZero, 50.0), impact_only;
  thx_msgs::physics_impact_t hit{};
  hit.utime = 500;
  hit.body_a = 0;
  hit.body_b = 1;
  hit.impulse = 1e-3;
  hit.v_approach = 0.5;
  hit.p_world[0] = 0.1;
  hit.p_world[2] = 0.3;
  hit.n_world[0] = -1.0;
  with_rest.impacts.push_back(hit);
  impact_only.poses = with_rest.poses;
  impact_only.impacts.push_back(hit);
  const PhysicsRender a = render(with_rest), b = render(impact_only);
  ASSERT_FALSE(b.samples.empty());
  EXPECT_EQ(a.samples, b.samples);
}

// The live path: PhysicsSource makes Micro events at a point on both balls; SynthScene, given
// them at their samples, plays what the offline render writes (float against double).
TEST(ObjectContacts, LiveMicroEventsPlayAsTheOfflineRender) {
  const SoundingScene& sc = twoBalls();
  const Eigen::Vector3d slip(0, 0.5, 0);
  const PhysicsStreams s = rubbing(slip, slip, 10.0);
  const PhysicsRender offline = render(s);

  PhysicsSource source(sc, {1, 2}, 1, 0);
  struct Sink final : ExcitationSink {
    std::vector<ExcitationEvent> events;
    void push(const ExcitationEvent& e) override { events.push_back(e); }
  } sink;
  source.physicsPoses(s.poses[0], 0);
  for (const auto& m : s.contacts) source.physicsContacts(m, 0, sink);
  ASSERT_EQ(sink.events.size(), std::size_t(2 * kReports));
  for (const ExcitationEvent& e : sink.events) {
    EXPECT_EQ(e.kind, ExcitationKind::Micro);
    EXPECT_EQ(e.point_count, 4);  // Tet4 balls
    EXPECT_EQ(e.end_ns - e.time_ns, 1'000'000);
  }

  std::vector<SoundingBody> bodies{soundingBody("surface", sc.surface->modes()), soundingBody("ball 0", sc.objects[0]->modes()),
                                   soundingBody("ball 1", sc.objects[1]->modes())};
  SynthScene synth(std::move(bodies), kFs, 4096, 1, std::make_shared<const RoughnessProfile>(sceneRoughness(sc.scene)));
  std::vector<float> live(offline.samples.size(), 0.0f);
  std::size_t done = 0;
  // The offline render's rounding of a time to its sample (from µs), so both place every segment alike.
  const auto sampleOf = [](std::int64_t ns) { return std::size_t(std::llround(double(ns / 1000) * 1e-6 * kFs)); };
  for (const ExcitationEvent& e : sink.events) {
    const std::size_t at = sampleOf(e.time_ns);
    if (at > done) synth.render(std::span<float>(live).subspan(done, at - done));
    done = std::max(done, at);
    ASSERT_TRUE(synth.strike(e, std::int64_t(sampleOf(e.end_ns)) - std::int64_t(at)));
  }
  synth.render(std::span<float>(live).subspan(done));
  double peak = 0, worst = 0;
  for (std::size_t n = 0; n < live.size(); ++n) {
    peak = std::max(peak, std::fabs(offline.samples[n]));
    worst = std::max(worst, std::fabs(double(live[n]) - offline.samples[n]));
  }
  std::printf("[measured] live against offline: largest difference %.3g of the peak %.3g\n", worst / peak, peak);
  ASSERT_GT(peak, 0.0);
  EXPECT_LT(worst, 1e-4 * peak);
}

}  // namespace
}  // namespace thx::audio::test_object_contacts
